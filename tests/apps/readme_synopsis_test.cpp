// The README's command-line synopsis against the tool's --help: the same options, command by
// command, so that neither drifts from the other.

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "support/cli_runner.h"

namespace {

using Options = std::set<std::string>;

// Options (--name, and -x short forms) in `text`.
Options options_in(const std::string& text) {
  static const std::regex option("(^|[\\s\\[(|])(--[a-z][a-z-]*|-[a-zA-Z])(?![\\w-])");
  Options out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), option);
       it != std::sregex_iterator(); ++it) {
    out.insert((*it)[2]);
  }
  return out;
}

// Each command's options in the README's synopsis block (the first ``` block of "## Command
// line"; a line not starting with "deformcd" continues the command above).
std::map<std::string, Options> readme_synopsis() {
  std::ifstream in(std::filesystem::path(DEFORMCD_SOURCE_DIR) / "README.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string readme = text.str();
  const std::size_t section = readme.find("## Command line\n");
  const std::size_t begin = readme.find("```\n", section) + 4;
  const std::size_t end = readme.find("```", begin);
  std::istringstream block(readme.substr(begin, end - begin));
  std::map<std::string, Options> commands;
  std::string command;
  for (std::string line; std::getline(block, line);) {
    std::istringstream words(line);
    std::string first, second;
    words >> first >> second;
    if (first == "deformcd") command = second;
    const std::string options = line.substr(0, line.find('#'));  // not the comments
    commands[command].merge(options_in(options));
  }
  return commands;
}

// The options `deformcd COMMAND --help` lists: "--name", or "-x|--name" for one with a short
// form, which the README may write either way.
struct HelpOptions {
  Options options;
  std::map<std::string, std::string> long_of_short;
};
HelpOptions help_options(const std::string& command) {
  const deformcd::test::CliRun r = deformcd::test::run_cli(command + " --help");
  EXPECT_EQ(r.status, 0) << r.output;
  static const std::regex option("^\\s+(?:(-\\w),)?(--[a-z][a-z-]*)");
  HelpOptions out;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, option) || m[2] == "--help") continue;
    out.options.insert(m[2]);
    if (m[1].matched) out.long_of_short[m[1]] = m[2];
  }
  return out;
}

TEST(ReadmeSynopsis, ListsEveryOptionOfEveryCommandAndNoOther) {
  const std::map<std::string, Options> readme = readme_synopsis();
  const std::string commands = deformcd::test::run_cli("--help").output;
  for (const char* command : {"info", "tetra", "run", "bench", "render", "view"}) {
    if (commands.find(std::string("  ") + command + " ") == std::string::npos)
      continue;  // not built
    ASSERT_TRUE(readme.count(command)) << "the README's synopsis has no " << command;
    const HelpOptions help = help_options(command);
    Options written;
    for (const std::string& o : readme.at(command)) {
      const auto alias = help.long_of_short.find(o);
      written.insert(alias == help.long_of_short.end() ? o : alias->second);
    }
    EXPECT_EQ(written, help.options) << command;
  }
}

}  // namespace
