#pragma once
// Each subcommand registers itself on the root app; its callback runs the library and prints.
#include <CLI/CLI.hpp>

namespace topple::cli {

void add_info_command(CLI::App& app);
void add_slide_command(CLI::App& app);
void add_invert_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_rock_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_spectrum_command(CLI::App& app);
void add_fragility_command(CLI::App& app);
void add_body_command(CLI::App& app);
void add_survey_form_command(CLI::App& app);
void add_campaign_command(CLI::App& app);

}  // namespace topple::cli
