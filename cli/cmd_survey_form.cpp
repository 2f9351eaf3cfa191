// topple survey-form: the offline survey form (output/survey_form.hpp), one self-contained HTML page, on stdout or
// into a file (--output, written whole or not at all).
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "progress.hpp"
#include "topple/core/output_file.hpp"
#include "topple/output/survey_form.hpp"

namespace topple::cli {

void add_survey_form_command(CLI::App& app) {
  auto output = std::make_shared<std::string>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "survey-form", "Print the offline survey form: one self-contained HTML page (no network, no server) where a field "
                     "team enters a site and its objects, sees the survey reader's errors as it types, and saves the "
                     "survey as TOML or CSV (docs/survey.md, \"The offline survey form\")");
  cmd->add_option("-o,--output", *output, "Write the page to this file instead of stdout");
  add_quiet_flag(*cmd, *quiet);  // nothing to silence: accepted so that every command takes --quiet
  // The callback owns both variables: CLI11 writes --quiet into *quiet while parsing, after this function returns.
  cmd->callback([output, quiet] {
    (void)quiet;
    const std::string page = io::survey_form_html();
    if (!output->empty()) {
      io::write_file_atomically(*output, page);
      return;
    }
    fmt::print("{}", page);
    std::fflush(stdout);
  });
}

}  // namespace topple::cli
