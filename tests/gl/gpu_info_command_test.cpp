// `deformcd info --gpu`: the table and the JSON object.

#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/deformcd/gpu_info_command.h"
#include "deformcd/backend.h"
#include "gl/gl_test_context.h"

namespace deformcd::app {
namespace {

using gl::test_support::ScopedEnv;

// Redirects std::cerr into a string for one scope.
class CaptureCerr {
 public:
  CaptureCerr() : old_(std::cerr.rdbuf(captured_.rdbuf())) {}
  ~CaptureCerr() { std::cerr.rdbuf(old_); }
  CaptureCerr(const CaptureCerr&) = delete;
  CaptureCerr& operator=(const CaptureCerr&) = delete;
  [[nodiscard]] std::string text() const { return captured_.str(); }

 private:
  std::ostringstream captured_;
  std::streambuf* old_;
};

class GpuInfoCommandTest : public gl::test_support::GlTest {};

TEST_F(GpuInfoCommandTest, PrintsOneJsonObjectWithTheLimits) {
  std::ostringstream out;
  ASSERT_EQ(run_gpu_info(out, true), 0);
  const nlohmann::json j = nlohmann::json::parse(out.str());
  ASSERT_TRUE(j.is_object());
  EXPECT_GE(j.at("gl_major").get<int>() * 10 + j.at("gl_minor").get<int>(), 43);
  EXPECT_FALSE(j.at("renderer").get<std::string>().empty());
  EXPECT_EQ(j.at("max_work_group_size").size(), 3u);
  EXPECT_GE(j.at("max_work_group_count")[0].get<std::uint32_t>(), 65535u);
  EXPECT_GT(j.at("max_ssbo_bytes").get<std::uint64_t>(), 0u);
  EXPECT_GE(j.at("max_ssbo_bindings").get<int>(), 8);
  for (const char* key : {"vendor", "gl_version", "glsl_version", "platform",
                          "max_work_group_invocations", "max_shared_memory_bytes"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  // The library's verdict on the device, for scripts (scripts/run.sh): the backend `auto`
  // chooses, GL on a hardware device only, and why not.
  const bool software = j.at("software_renderer").get<bool>();
  EXPECT_EQ(software, is_software_renderer(j.at("renderer").get<std::string>()));
  EXPECT_EQ(j.at("auto_backend").get<std::string>(), software ? "cpu" : "gl");
  EXPECT_EQ(j.at("auto_backend_reason").get<std::string>().empty(), !software);
}

TEST_F(GpuInfoCommandTest, PrintsAnAlignedTable) {
  std::ostringstream out;
  ASSERT_EQ(run_gpu_info(out, false), 0);
  const std::string table = "\n" + out.str();
  for (const char* label :
       {"vendor", "renderer", "GL version", "GLSL version", "platform", "max work-group count",
        "max work-group size", "max invocations", "max SSBO size", "max SSBO bindings"}) {
    EXPECT_NE(table.find(std::string("\n") + label + " "), std::string::npos) << label << " in\n"
                                                                              << table;
  }
  EXPECT_NE(table.find(" MiB)"), std::string::npos) << table;
  // Aligned: every value starts in the same column.
  std::istringstream lines(out.str());
  for (std::string line; std::getline(lines, line);) {
    ASSERT_GE(line.size(), 23u) << line;
    EXPECT_EQ(line[21], ' ') << line;
    EXPECT_NE(line[22], ' ') << line;
  }
}

TEST(GpuInfoCommand, ContextFailureGoesToStderrWithStatus1) {
  ScopedEnv env("DEFORMCD_EGL_PLATFORM", "nonsense");
  CaptureCerr cerr;
  std::ostringstream out;
  EXPECT_EQ(run_gpu_info(out, false), 1);
  EXPECT_TRUE(out.str().empty());
  EXPECT_EQ(cerr.text(),
            "deformcd: DEFORMCD_EGL_PLATFORM='nonsense' is not one of auto, device, surfaceless\n");
}

}  // namespace
}  // namespace deformcd::app
