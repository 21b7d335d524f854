#include "bench_report.h"

#include <algorithm>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "bench_intersections.h"

namespace deformcd::app {

namespace {

nlohmann::json per_stage(const std::array<double, 3>& values) {
  nlohmann::json j;
  for (int s = 0; s < 3; ++s)
    j[kStageNames[s]] = values[s];
  return j;
}

nlohmann::json milliseconds(const std::vector<double>& seconds) {
  nlohmann::json j = nlohmann::json::array();
  for (double s : seconds)
    j.push_back(1e3 * s);
  return j;
}

// RFC 4180: quoted when it holds a comma, a quote or a line break (a GL device string does).
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// What the device times of a scene are: "none" (CPU backend), "gpu", or "cpu" (GL on a
// software renderer).
std::string device_times_name(DeviceTimes times) {
  return times == DeviceTimes::kGpu ? "gpu" : times == DeviceTimes::kCpu ? "cpu" : "none";
}

std::uint64_t candidates(const MethodRun& r) {
  return std::accumulate(r.candidates.begin(), r.candidates.end(), std::uint64_t{0});
}

}  // namespace

namespace {

// "12.3  45.6  -": a value per stage (before, contact, after), each in `width` columns; "-" for
// a stage without frames (a run never in contact), whose mean is not 0 but undefined.
std::string per_stage_columns(const std::array<double, 3>& values, const std::array<int, 3>& frames,
                              int width) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(1);
  for (int s = 0; s < 3; ++s) {
    if (frames[s] == 0) {
      text << std::setw(width) << "-";
    } else {
      text << std::setw(width) << values[s];
    }
  }
  return text.str();
}

constexpr int kStageWidth = 9;  // one stage's column
constexpr int kStagesWidth = 3 * kStageWidth;

// The paper's summary: each method against the first (V1).
void print_summary(std::ostream& out, const SceneBench& b) {
  if (b.runs.size() < 2) return;
  const MethodRun& base = b.runs.front();
  out << "Total run time V (simulation + collision detection), each method against "
      << broadphase_name(base.method) << " (V1):\n";
  out << std::left << std::setw(16) << "method" << std::right << std::setw(10) << "V1 (s)"
      << std::setw(10) << "V2 (s)" << std::setw(10) << "I" << std::setw(9) << "V1/V2"
      << std::setw(11) << "CD V1/V2" << '\n';
  for (std::size_t m = 1; m < b.runs.size(); ++m) {
    const MethodRun& r = b.runs[m];
    out << std::left << std::setw(16) << broadphase_name(r.method) << std::right
        << std::setprecision(3) << std::setw(10) << base.total_s() << std::setw(10) << r.total_s()
        << std::setprecision(1) << std::setw(9) << 100.0 * improvement(base.total_s(), r.total_s())
        << "%" << std::setprecision(2) << std::setw(9) << base.total_s() / r.total_s()
        << std::setw(11) << base.total_collision_s() / r.total_collision_s() << '\n';
  }
  out << "(I = (V1 - V2) / V2 as in the paper; CD = the collision-detection stage alone)\n";
}

// Each method's times: totals, then per frame in each of the paper's three phases.
void print_detail(std::ostream& out, const SceneBench& b) {
  out << std::left << std::setw(16) << "" << std::right << std::setw(30) << "total"
      << std::setw(kStagesWidth + 2) << "ms per frame (sim + CD)" << std::setw(kStagesWidth + 2)
      << "CD ms per frame" << '\n';
  out << std::left << std::setw(16) << "method" << std::right << std::setw(10) << "V (s)"
      << std::setw(10) << "sim (s)" << std::setw(10) << "CD (s)"
      << "  ";
  for (int column = 0; column < 2; ++column) {
    for (const char* stage : kStageNames)
      out << std::setw(kStageWidth) << stage;
    out << "  ";
  }
  out << std::setw(10) << "pairs" << '\n';
  for (const MethodRun& r : b.runs) {
    const StageTimes t = stage_times(r, b.stages);
    out << std::left << std::setw(16) << broadphase_name(r.method) << std::right
        << std::setprecision(3) << std::setw(10) << r.total_s() << std::setw(10)
        << r.total_simulation_s() << std::setw(10) << r.total_collision_s() << "  "
        << per_stage_columns(t.ms_per_frame, t.frames, kStageWidth) << "  "
        << per_stage_columns(t.collision_ms_per_frame, t.frames, kStageWidth) << "  "
        << std::setw(10) << r.pairs() << '\n';
  }
}

// Timer queries mean something on a GPU only: on a software renderer they read about 0 (see
// deformcd/gl/timer_query.h), so a table of them would mislead.
void print_device_times(std::ostream& out, const SceneBench& b) {
  if (b.device_times == DeviceTimes::kCpu) {
    out << "(no device-time table: the renderer is a software one, whose timer queries do not "
           "time compute dispatches; the wall clock above is the measure)\n";
  }
  if (b.device_times != DeviceTimes::kGpu) return;
  out << "device time (GL timer queries, GL_TIME_ELAPSED):\n";
  out << std::left << std::setw(16) << "" << std::right << std::setw(kStagesWidth + 2)
      << "ms per frame (sim + CD)" << std::setw(kStagesWidth + 2) << "CD ms per frame" << '\n';
  out << std::left << std::setw(16) << "method" << std::right << "  ";
  for (int column = 0; column < 2; ++column) {
    for (const char* stage : kStageNames)
      out << std::setw(kStageWidth) << stage;
    out << "  ";
  }
  out << '\n';
  for (const MethodRun& r : b.runs) {
    const StageTimes t = stage_times(r, b.stages);
    out << std::left << std::setw(16) << broadphase_name(r.method) << std::right << "  "
        << per_stage_columns(t.device_ms_per_frame, t.frames, kStageWidth) << "  "
        << per_stage_columns(t.collision_device_ms_per_frame, t.frames, kStageWidth) << '\n';
  }
}

void print_response(std::ostream& out, const SceneBench& b) {
  if (b.runs.empty() || b.runs.front().proximity_s.empty()) return;
  out << "contact response (in the simulation time above), ms/frame:\n";
  for (const MethodRun& r : b.runs) {
    const double frames = static_cast<double>(r.proximity_s.size());
    const double simulation = r.total_simulation_s() - r.total_proximity_s() - r.total_response_s();
    out << std::left << std::setw(16) << broadphase_name(r.method) << std::right << std::fixed
        << std::setprecision(2) << "simulation " << 1e3 * simulation / frames << ", proximity "
        << 1e3 * r.total_proximity_s() / frames << ", response "
        << 1e3 * r.total_response_s() / frames << " (proximity + response = "
        << (r.total_proximity_s() + r.total_response_s()) / simulation
        << " x the simulation); searches "
        << static_cast<double>(
               std::accumulate(r.searches.begin(), r.searches.end(), std::uint64_t{0})) /
               frames
        << ", widenings "
        << static_cast<double>(
               std::accumulate(r.widenings.begin(), r.widenings.end(), std::uint64_t{0})) /
               frames;
    const std::uint64_t self_searches =
        std::accumulate(r.self_searches.begin(), r.self_searches.end(), std::uint64_t{0});
    if (self_searches > 0) {
      out << ", bodies searched against themselves " << static_cast<double>(self_searches) / frames;
    }
    const auto [fewest, most] = std::minmax_element(r.substeps.begin(), r.substeps.end());
    if (fewest != r.substeps.end() && *fewest != *most) {  // motion-bounded substeps
      out << ", substeps "
          << static_cast<double>(
                 std::accumulate(r.substeps.begin(), r.substeps.end(), std::uint64_t{0})) /
                 frames
          << " (" << *fewest << "-" << *most << ")";
    }
    out << " a frame";
    const std::uint64_t substeps =
        std::accumulate(r.substeps.begin(), r.substeps.end(), std::uint64_t{0});
    if (substeps > 0) {
      out << "; iterations "
          << static_cast<double>(
                 std::accumulate(r.iterations.begin(), r.iterations.end(), std::uint64_t{0})) /
                 static_cast<double>(substeps)
          << " a substep";
    }
    out << "\n";
    // The frames in contact apart (constraints between bodies: with self-contact every frame
    // has each body's own): the response costs less in the others.
    const auto in_contact = static_cast<std::size_t>(std::count_if(
        r.constraints_between.begin(), r.constraints_between.end(), [](auto c) { return c > 0; }));
    const std::size_t apart = r.constraints_between.size() - in_contact;
    out << std::setw(16) << "";
    if (in_contact == 0) {
      out << "no frame ended with constraints between bodies";
    } else {
      out << "the " << in_contact << " frames ending with constraints between bodies: proximity + "
          << "response = " << r.response_ratio(true) << " x the simulation";
      if (apart != 0) out << "; the other " << apart << ": " << r.response_ratio(false) << " x";
    }
    // A pile or a stack should end asleep (ResponseSettings::sleep): how many, and since when.
    if (!r.asleep.empty() && r.asleep.back() > 0) {
      const auto since = std::find_if(r.asleep.rbegin(), r.asleep.rend(),
                                      [&](auto a) { return a != r.asleep.back(); });
      out << "; " << r.asleep.back() << " bodies asleep at the end, since frame "
          << r.asleep.size() - static_cast<std::size_t>(since - r.asleep.rbegin()) + 1;
    }
    out << '\n' << std::defaultfloat;
    print_intersection_summary(out, r.intersections, r.inverted_tetrahedra);
  }
}

}  // namespace

void print_bench_table(std::ostream& out, const SceneBench& b) {
  const int contact = static_cast<int>(std::count(b.stages.begin(), b.stages.end(), kContact));
  out << std::fixed << "\n== " << b.scene << " on " << b.backend << " (" << b.device << "), "
      << b.frames << " frames, " << contact << " in contact ==\n";
  print_summary(out, b);
  print_detail(out, b);
  print_device_times(out, b);
  print_response(out, b);
  // Each row is its own stretch of time: a load that comes or goes during the run weighs on
  // the rows unequally, which a reader comparing them must know.
  if (b.runs.size() > 1) {
    out << "Rows measured one after the other (each method's whole run, then the next): a "
           "machine whose load changes meanwhile times them unequally.\n";
  }
  out << "Times: wall clock around each stage"
      << (b.backend == "gl" ? " after waiting for the backend (glFinish)" : "")
      << "; warm-up runs excluded" << (b.repeat > 1 ? "; the median of the repeats" : "") << ".\n";
  for (const std::string& m : b.disagreements) {
    out << "WARNING: " << m << " found different contacts from "
        << broadphase_name(b.runs.front().method) << " on some frame\n";
  }
  out << std::defaultfloat;
}

std::string bench_json(const std::vector<SceneBench>& results, const BenchRecord& record) {
  nlohmann::json scenes = nlohmann::json::array();
  for (const SceneBench& b : results) {
    nlohmann::json methods = nlohmann::json::object();
    nlohmann::json improvements = nlohmann::json::object();
    nlohmann::json speedups = nlohmann::json::object();
    nlohmann::json collision_speedups = nlohmann::json::object();
    const MethodRun& base = b.runs.front();
    for (const MethodRun& r : b.runs) {
      const StageTimes t = stage_times(r, b.stages);
      const std::string name(broadphase_name(r.method));
      nlohmann::json frames_per_stage;
      for (int s = 0; s < 3; ++s)
        frames_per_stage[kStageNames[s]] = t.frames[s];
      nlohmann::json per_frame = {{"simulation_ms", milliseconds(r.simulation_s)},
                                  {"collision_ms", milliseconds(r.collision_s)},
                                  {"contacts", r.contacts},
                                  {"candidates", r.candidates}};
      if (!r.proximity_s.empty()) {
        per_frame["proximity_ms"] = milliseconds(r.proximity_s);
        per_frame["response_ms"] = milliseconds(r.response_s);
        per_frame["searches"] = r.searches;
        per_frame["widenings"] = r.widenings;
        per_frame["iterations"] = r.iterations;
        per_frame["self_searches"] = r.self_searches;
        per_frame["substeps"] = r.substeps;
        per_frame["asleep"] = r.asleep;
        per_frame["constraints"] = r.constraints;
        per_frame["constraints_between"] = r.constraints_between;
      }
      add_intersection_fields(per_frame, r.intersections, r.inverted_tetrahedra);
      methods[name] = {{"total_s", r.total_s()},
                       {"simulation_s", r.total_simulation_s()},
                       {"collision_s", r.total_collision_s()},
                       {"ms_per_frame", per_stage(t.ms_per_frame)},
                       {"collision_ms_per_frame", per_stage(t.collision_ms_per_frame)},
                       {"frames_per_stage", frames_per_stage},
                       {"pairs", r.pairs()},
                       {"candidates", candidates(r)},
                       {"per_frame", per_frame}};
      if (!r.proximity_s.empty()) {
        methods[name]["proximity_s"] = r.total_proximity_s();
        methods[name]["response_s"] = r.total_response_s();
      }
      if (t.device_times) {
        nlohmann::json& m = methods[name];
        m["device_simulation_s"] = r.total_simulation_device_s();
        m["device_collision_s"] = r.total_collision_device_s();
        m["device_ms_per_frame"] = per_stage(t.device_ms_per_frame);
        m["collision_device_ms_per_frame"] = per_stage(t.collision_device_ms_per_frame);
        m["per_frame"]["simulation_device_ms"] = milliseconds(r.simulation_device_s);
        m["per_frame"]["collision_device_ms"] = milliseconds(r.collision_device_s);
      }
      if (&r == &base) continue;
      improvements[name] = improvement(base.total_s(), r.total_s());
      speedups[name] = base.total_s() / r.total_s();
      collision_speedups[name] = base.total_collision_s() / r.total_collision_s();
    }
    scenes.push_back({{"scene", b.scene},
                      {"backend", b.backend},
                      {"device", b.device},
                      {"frames", b.frames},
                      {"baseline", std::string(broadphase_name(base.method))},
                      {"methods", methods},
                      {"improvement", improvements},
                      {"speedup", speedups},
                      {"collision_speedup", collision_speedups},
                      {"methods_agree", b.disagreements.empty()},
                      {"device_times", device_times_name(b.device_times)}});
  }
  return nlohmann::json{{"deformcd_version", record.version},
                        {"repeat", record.repeat},
                        {"warmup_frames", record.warmup_frames},
                        {"threads", record.threads},
                        {"scenes", scenes}}
             .dump(2) +
         "\n";
}

std::string bench_csv(const std::vector<SceneBench>& results, const BenchRecord& record) {
  std::ostringstream out;
  out << "scene,backend,device,method,frames,repeat,threads,total_s,simulation_s,collision_s,"
         "ms_before,ms_contact,ms_after,cd_ms_before,cd_ms_contact,cd_ms_after,pairs,"
         "candidates,improvement,deformcd_version,device_times,device_ms_before,"
         "device_ms_contact,device_ms_after,cd_device_ms_before,cd_device_ms_contact,"
         "cd_device_ms_after\n";
  out << std::setprecision(9);
  for (const SceneBench& b : results) {
    const MethodRun& base = b.runs.front();
    for (const MethodRun& r : b.runs) {
      const StageTimes t = stage_times(r, b.stages);
      out << csv_field(b.scene) << ',' << b.backend << ',' << csv_field(b.device) << ','
          << broadphase_name(r.method) << ',' << b.frames << ',' << record.repeat << ','
          << record.threads << ',' << r.total_s() << ',' << r.total_simulation_s() << ','
          << r.total_collision_s();
      for (double v : t.ms_per_frame)
        out << ',' << v;
      for (double v : t.collision_ms_per_frame)
        out << ',' << v;
      out << ',' << r.pairs() << ',' << candidates(r) << ','
          << improvement(base.total_s(), r.total_s()) << ',' << record.version << ','
          << device_times_name(b.device_times);
      // Empty fields where nothing was measured (the CPU backend).
      for (const auto* values : {&t.device_ms_per_frame, &t.collision_device_ms_per_frame}) {
        for (double v : *values) {
          out << ',';
          if (t.device_times) out << v;
        }
      }
      out << '\n';
    }
  }
  return out.str();
}

}  // namespace deformcd::app
