// docs/cli.md against the tool: a section "## `deformcd COMMAND`" for every command that
// `deformcd --help` lists, and in it an options table whose rows name exactly the options that
// `deformcd COMMAND --help` lists. The failures say what is missing where, so that a change of
// the tool shows which lines of the page to write.

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
const char* const kPage = "docs/cli.md";

// Options (--name, and -x short forms) in `text`.
Options options_in(const std::string& text) {
  static const std::regex option("(^|[\\s\\[(|`,/])(--[a-z][a-z-]*|-[a-zA-Z])(?![\\w-])");
  Options out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), option);
       it != std::sregex_iterator(); ++it) {
    out.insert((*it)[2]);
  }
  return out;
}

struct Section {
  int line = 0;     // of the heading
  Options options;  // from the first cells of the table rows "| `-..."
};

// Each "## `deformcd COMMAND`" section of the page and the options its table rows name.
std::map<std::string, Section> page_sections() {
  std::ifstream in(std::filesystem::path(DEFORMCD_SOURCE_DIR) / kPage);
  std::map<std::string, Section> sections;
  static const std::regex heading("^## `deformcd ([a-z][a-z-]*)`");
  std::string command;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    std::smatch m;
    if (std::regex_search(line, m, heading)) {
      command = m[1];
      sections[command].line = number;
      continue;
    }
    if (line.rfind("## ", 0) == 0) command.clear();
    if (command.empty() || line.rfind("| `-", 0) != 0) continue;
    const std::size_t end = line.find('|', 1);
    sections[command].options.merge(options_in(line.substr(1, end - 1)));
  }
  return sections;
}

// The commands `deformcd --help` lists ("  run   Simulate ...").
std::set<std::string> help_commands() {
  const deformcd::test::CliRun r = deformcd::test::run_cli("--help");
  EXPECT_EQ(r.status, 0) << r.output;
  static const std::regex command("^  ([a-z][a-z-]*)\\s");
  std::set<std::string> out;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, command)) out.insert(m[1]);
  }
  return out;
}

// The options `deformcd COMMAND --help` lists: "--name", or "-x,--name" for one with a short
// form, which the page may write either way.
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

TEST(CliReference, HasASectionForEveryCommand) {
  const std::map<std::string, Section> sections = page_sections();
  const std::set<std::string> commands = help_commands();
  ASSERT_FALSE(commands.empty());
  for (const std::string& command : commands) {
    EXPECT_TRUE(sections.count(command))
        << kPage << " has no section \"## `deformcd " << command << "`\" for the command that "
        << "`deformcd --help` lists";
  }
}

TEST(CliReference, ListsEveryOptionOfEveryCommandAndNoOther) {
  const std::map<std::string, Section> sections = page_sections();
  for (const std::string& command : help_commands()) {
    const auto section = sections.find(command);
    if (section == sections.end()) continue;  // HasASectionForEveryCommand says so
    const HelpOptions help = help_options(command);
    Options written;
    for (const std::string& o : section->second.options) {
      const auto alias = help.long_of_short.find(o);
      written.insert(alias == help.long_of_short.end() ? o : alias->second);
    }
    for (const std::string& o : help.options) {
      EXPECT_TRUE(written.count(o))
          << kPage << ":" << section->second.line << ": the section of `deformcd " << command
          << "` has no row for " << o << ", which `deformcd " << command
          << " --help` lists: add \"| `" << o << " ...` | meaning |\" to its options table";
    }
    for (const std::string& o : written) {
      EXPECT_TRUE(help.options.count(o))
          << kPage << ":" << section->second.line << ": the section of `deformcd " << command
          << "` documents " << o << ", which `deformcd " << command
          << " --help` does not list: remove its row";
    }
  }
}

}  // namespace
