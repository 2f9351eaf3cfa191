// topple: earthquake response of free-standing rigid objects. Exit statuses: topple::ExitStatus (error.hpp): 0 success,
// 1 internal error, 2 bad input, 3 solver limit, 4 output failure, 130/143 SIGINT/SIGTERM.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "commands.hpp"
#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"

namespace {

/// Every option that takes a value refuses an empty one (`--azimuth ''`, `--support-freq ''`), naming the option:
/// an empty text read as 0, as "no support" or as the default would be a silent guess. One validator on every
/// valued option of every subcommand, so that an option added later gets it too; flags take no value.
void refuse_empty_values(CLI::App& app) {
  const CLI::Validator non_empty(
      [](std::string& value) {
        return value.empty() ? std::string("the value is empty: give one, or leave the option out") : std::string();
      },
      "");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_size_max() > 0) option->check(non_empty);
  }
  for (CLI::App* sub : app.get_subcommands({})) refuse_empty_values(*sub);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"topple: sliding, rocking and overturning of rigid objects in earthquakes, and what they tell "
               "about the shaking"};
  topple::io::install_interrupt_cleanup();
  app.require_subcommand(1);
  app.set_version_flag("--version", "topple 0.1.0");
  topple::cli::add_info_command(app);
  topple::cli::add_slide_command(app);
  topple::cli::add_invert_command(app);
  topple::cli::add_synth_command(app);
  topple::cli::add_rock_command(app);
  topple::cli::add_sweep_command(app);
  topple::cli::add_spectrum_command(app);
  topple::cli::add_fragility_command(app);
  topple::cli::add_body_command(app);
  topple::cli::add_survey_form_command(app);
  topple::cli::add_campaign_command(app);
  refuse_empty_values(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const topple::InputError& e) {
    fmt::print(stderr, "topple: error: {}\n", e.what());
    return static_cast<int>(topple::ExitStatus::bad_input);
  } catch (const topple::SolverError& e) {
    fmt::print(stderr, "topple: solver limit: {}\n", e.what());
    return static_cast<int>(topple::ExitStatus::solver_limit);
  } catch (const topple::OutputError& e) {
    fmt::print(stderr, "topple: output error: {}\n", e.what());
    return static_cast<int>(topple::ExitStatus::output_failure);
  } catch (const std::exception& e) {
    fmt::print(stderr, "topple: internal error: {}\n", e.what());
    return static_cast<int>(topple::ExitStatus::internal_error);
  }
  return 0;
}
