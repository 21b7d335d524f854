#include "option_values.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "deformcd/collision.h"
#include "deformcd/limits.h"
#include "usage_error.h"

namespace deformcd::app {

void add_frames_option(CLI::App* command, std::optional<int>& frames) {
  command->add_option("--frames", frames,
                      "Length of the run in frames (default: the scene's settings.frames); the "
                      "bodies' paths span exactly this many");
}

void add_broadphase_option(CLI::App* command, std::optional<std::string>& broadphase,
                           bool none_ok) {
  std::vector<std::string> valid;
  if (none_ok) valid.emplace_back("none");
  for (const std::string& name : broadphase_names())
    valid.push_back(name);
  std::string list;
  for (const std::string& name : valid)
    list += (list.empty() ? "" : ", ") + name;
  command
      ->add_option("--broadphase", broadphase,
                   "Collision broad phase: " + list +
                       " (default: the scene's collision.broadphase, itself bvh by default)")
      ->check(CLI::Validator(
          [valid, list](std::string& name) -> std::string {
            if (std::find(valid.begin(), valid.end(), name) != valid.end()) return {};
            return "unknown broad phase '" + name + "' (valid: " + list + ")";
          },
          "METHOD"));
}

void check_at_least(const char* option, long value, long minimum) {
  if (value < minimum) {
    throw UsageError(std::string(option) + " must be at least " + std::to_string(minimum) +
                     ", got " + std::to_string(value));
  }
}

void check_threads_option(long threads) {
  try {
    check_thread_count("--threads", threads);
  } catch (const InputError& e) {
    throw UsageError(e.what());
  }
}

void check_run_length(long long frames, long long substeps) {
  const long long total = frames * substeps;  // both below 2^31: no overflow
  const char* lifted = std::getenv("DEFORMCD_LONG_RUN");
  if (total <= kMaxRunSubsteps || (lifted != nullptr && std::string(lifted) == "1")) return;
  throw UsageError("the run is " + std::to_string(frames) + " frames x " +
                   std::to_string(substeps) + " substeps = " + std::to_string(total) +
                   " substeps, more than " + std::to_string(kMaxRunSubsteps) +
                   " (the longest shipped scene takes 9600): set DEFORMCD_LONG_RUN=1 to run it "
                   "anyway, or give fewer --frames");
}

std::string count_of(std::uint64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace deformcd::app
