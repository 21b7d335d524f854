// Fuzz target of the scene reader, through the public read_scene: each input is written to
// WORK/scenes/fuzz.json, where WORK is a scratch directory holding a link `assets` to the
// shipped assets, so that the shipped scenes' "../assets/models/..." resolve and the fuzzer
// reaches every check past the model's existence. Models are not loaded (the mesh targets
// cover their readers).
//
// Its first finding, a number no double holds ("1e400") escaping read_scene as nlohmann's
// out_of_range, is fixed in src/scene/scene_reader.cpp; a seed keeps replaying it.

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "deformcd/scene.h"
#include "fuzz_support.h"

namespace {

namespace fs = std::filesystem;

fs::path g_work;
fs::path g_scene;

void remove_work() {
  std::error_code ignored;
  fs::remove_all(g_work, ignored);
}

// libFuzzer often ends without running atexit handlers (a finding, -max_total_time), so each
// run also removes the scratch directories of runs that are gone: they are named by pid.
void remove_stale_work(const fs::path& tmp) {
  constexpr std::string_view kPrefix = "deformcd_fuzz_scene_";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(tmp, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with(kPrefix)) continue;
    const long pid = std::strtol(name.c_str() + kPrefix.size(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const fs::path tmp = fs::temp_directory_path();
  remove_stale_work(tmp);
  g_work = tmp / ("deformcd_fuzz_scene_" + std::to_string(::getpid()));
  fs::remove_all(g_work);
  fs::create_directories(g_work / "scenes");
  std::atexit(remove_work);
  fs::create_directory_symlink(fs::path(DEFORMCD_SOURCE_DIR) / "assets", g_work / "assets");
  g_scene = g_work / "scenes" / "fuzz.json";
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::FILE* out = std::fopen(g_scene.c_str(), "wb");
  if (!out || std::fwrite(data, 1, size, out) != size || std::fclose(out) != 0) {
    deformcd::fuzz::finding("cannot write " + g_scene.string());
  }
  (void)deformcd::fuzz::reads_or_rejects([] { (void)deformcd::read_scene(g_scene); },
                                         g_scene.string());
  return 0;
}
