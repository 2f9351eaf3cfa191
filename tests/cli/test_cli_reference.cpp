// docs/cli.md, the command reference, kept true: every subcommand of `topple` (as its --help lists them, nested ones
// such as `spectrum slide` included) has a section headed `topple <command>`, and every long option a command's
// --help prints has a row of its own (the option in a table row's first cell) in that section or in a section of
// common options the section links to (`](#anchor)`). A command or an option added without its row in docs/cli.md
// fails here, naming what is missing; a mention in another option's text does not count.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"

namespace topple {
namespace {

/// One command's --help, parsed: its long options (first column of "Options:", --help left out) and its
/// subcommands (first column of "Subcommands:").
struct HelpPage {
  std::vector<std::string> options;
  std::vector<std::string> subcommands;
};

/// CLI11's help layout: a section title at column 0 ("Options:", "Subcommands:", "Positionals:"), entries indented
/// by two spaces with their names first; a long description wraps onto a line indented further, which never starts
/// with a name at column 2.
HelpPage parse_help(const std::string& text) {
  HelpPage page;
  std::istringstream in(text);
  std::string line;
  std::string section;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] != ' ') {
      section = line;
      continue;
    }
    if (line.size() < 3 || line[0] != ' ' || line[1] != ' ' || line[2] == ' ') continue;  // a wrapped description
    const std::string first = line.substr(2, line.find(' ', 2) - 2);
    if (section == "Options:") {
      // "-o,--output": the names are comma-separated; only the long ones are looked for.
      std::istringstream names(first);
      std::string name;
      while (std::getline(names, name, ',')) {
        if (name.rfind("--", 0) == 0 && name != "--help") page.options.push_back(name);
      }
    } else if (section == "Subcommands:") {
      page.subcommands.push_back(first);
    }
  }
  return page;
}

/// Whether `option` stands in `text` as a whole name: `--h` is not found in `--h2` or `--height`.
bool names_option(const std::string& text, const std::string& option) {
  for (std::size_t at = text.find(option); at != std::string::npos; at = text.find(option, at + 1)) {
    const std::size_t end = at + option.size();
    const bool ends = end == text.size() || !(std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-');
    const bool starts = at == 0 || !(std::isalnum(static_cast<unsigned char>(text[at - 1])) || text[at - 1] == '-');
    if (ends && starts) return true;
  }
  return false;
}

/// Whether `option` has a row in `text`: a table row (a line starting with '|') whose first cell names it.
bool has_row(const std::string& text, const std::string& option) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind('|', 0) != 0) continue;
    const std::size_t end = line.find('|', 1);
    if (names_option(line.substr(1, end == std::string::npos ? std::string::npos : end - 1), option)) return true;
  }
  return false;
}

/// GitHub's anchor of a heading: lower case, spaces to '-', punctuation other than '-' and '_' dropped.
std::string anchor_of(const std::string& heading) {
  std::string out;
  for (const char c : heading) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u)) {
      out += static_cast<char>(std::tolower(u));
    } else if (c == ' ' || c == '-') {
      out += '-';
    } else if (c == '_') {
      out += '_';
    }
  }
  return out;
}

/// docs/cli.md cut at its headings: the heading's text (without the #s and backticks) to the text up to the next
/// heading of any level; and the anchors of the headings to their text.
struct Reference {
  std::map<std::string, std::string> sections;
  std::map<std::string, std::string> by_anchor;
};

Reference read_reference(const std::string& markdown) {
  Reference ref;
  std::istringstream in(markdown);
  std::string line;
  std::string current;
  bool fenced = false;  // a '#' at the start of a line of a code block is a shell comment, not a heading
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    if (!fenced && line.rfind('#', 0) == 0) {
      std::string title = line.substr(line.find_first_not_of('#'));
      title.erase(std::remove(title.begin(), title.end(), '`'), title.end());
      title.erase(0, title.find_first_not_of(' '));
      current = title;
      ref.sections[current];
      ref.by_anchor[anchor_of(current)] = current;
      continue;
    }
    ref.sections[current] += line + "\n";
  }
  return ref;
}

/// The text a command's options may be named in: its section and the sections it links to within the page.
std::string reachable_text(const Reference& ref, const std::string& section) {
  const std::string& own = ref.sections.at(section);
  std::string text = own;
  for (std::size_t at = own.find("](#"); at != std::string::npos; at = own.find("](#", at + 1)) {
    const std::size_t end = own.find(')', at);
    if (end == std::string::npos) break;
    const auto linked = ref.by_anchor.find(own.substr(at + 3, end - at - 3));
    if (linked != ref.by_anchor.end()) text += ref.sections.at(linked->second);
  }
  return text;
}

TEST(CliReference, EveryCommandAndLongOptionIsInDocsCliMd) {
  const auto doc_path = std::filesystem::path(TOPPLE_SOURCE_DIR) / "docs" / "cli.md";
  const std::string markdown = test::slurp(doc_path);
  ASSERT_FALSE(markdown.empty()) << doc_path << " is missing or empty";
  const Reference ref = read_reference(markdown);

  const auto root = test::run_cli("--help");
  ASSERT_EQ(root.exit_code, 0) << root.err;
  const HelpPage root_page = parse_help(root.out);
  // main.cpp registers eleven subcommands; a parser that finds none would make this test pass on anything.
  ASSERT_GE(root_page.subcommands.size(), 11u) << root.out;
  ASSERT_FALSE(root_page.options.empty()) << root.out;  // --version

  std::vector<std::string> missing;
  for (const auto& option : root_page.options) {
    if (!has_row(markdown, option)) missing.push_back("topple " + option);
  }
  std::vector<std::string> pending = root_page.subcommands;
  std::set<std::string> commands;
  std::size_t options_checked = 0;
  while (!pending.empty()) {
    const std::string command = pending.front();
    pending.erase(pending.begin());
    commands.insert(command);
    const auto help = test::run_cli(command + " --help");
    ASSERT_EQ(help.exit_code, 0) << command << ": " << help.err;
    const HelpPage page = parse_help(help.out);
    for (const auto& sub : page.subcommands) pending.push_back(command + " " + sub);
    const std::string section = "topple " + command;
    if (!ref.sections.contains(section)) {
      missing.push_back("section '## " + section + "'");
      continue;
    }
    const std::string text = reachable_text(ref, section);
    for (const auto& option : page.options) {
      ++options_checked;
      if (!has_row(text, option)) missing.push_back(section + " " + option);
    }
  }
  EXPECT_TRUE(missing.empty()) << doc_path.string() << " has no row for (in the command's section or a section it "
                               << "links to):\n  " << [&] {
                                    std::string list;
                                    for (const auto& m : missing) list += m + "\n  ";
                                    return list;
                                  }();
  // Every command has options beyond --help; fewer than this many means the help was not parsed.
  EXPECT_GE(options_checked, 200u);

  // The other way: no section documents a command that no longer exists.
  for (const auto& [title, text] : ref.sections) {
    if (title.rfind("topple ", 0) != 0) continue;
    EXPECT_TRUE(commands.contains(title.substr(7))) << "docs/cli.md has a section for '" << title
                                                    << "', which `topple --help` does not list";
  }
}

TEST(CliReference, HelpParserReadsCli11Layout) {
  // The layout CLI11 2.x prints: names first at column 2, wrapped descriptions further in.
  const HelpPage page = parse_help(
      "Usage: topple x [OPTIONS]\n\nOptions:\n  -h,--help                   Print this help\n"
      "  -o,--output TEXT            Write\n  --shape TEXT Excludes: --body --mesh\n"
      "                              block --width\n  --h TEXT                    height\n\n"
      "Subcommands:\n  slide                       Max\n  rock                        Map\n");
  EXPECT_EQ(page.options, (std::vector<std::string>{"--output", "--shape", "--h"}));
  EXPECT_EQ(page.subcommands, (std::vector<std::string>{"slide", "rock"}));
  EXPECT_TRUE(names_option("`--h` and `--h2`", "--h"));
  EXPECT_FALSE(names_option("`--h2` and `--height`", "--h"));
  EXPECT_TRUE(has_row("text\n| `-o`, `--output` | text | — | Write |\n", "--output"));
  EXPECT_FALSE(has_row("| `--pose` | text | `rest` | or --up, --face |\n--output\n", "--face"));
  EXPECT_EQ(anchor_of("Record input options"), "record-input-options");
  EXPECT_EQ(anchor_of("topple spectrum slide"), "topple-spectrum-slide");
}

}  // namespace
}  // namespace topple
