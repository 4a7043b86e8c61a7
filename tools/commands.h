// The verbs of the insitu CLI, one file each (cmd_*.cpp). Each registers its subcommand with
// CLI11 and returns the function that runs it once parsed; bad input is thrown as InputError and
// reported by main (insitu.cpp).
#pragma once
#include <CLI/CLI.hpp>

#include <functional>

#include "core/error.h"

namespace insitu {

using Command = std::function<int()>;

Command add_render_command(CLI::App& app);
Command add_calibrate_command(CLI::App& app);
Command add_cubemap_command(CLI::App& app);
Command add_irradiance_report_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_tradeoff_command(CLI::App& app);
Command add_export_blender_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_batch_command(CLI::App& app);
Command add_studio_command(CLI::App& app);
Command add_modes_command(CLI::App& app);

void print_warnings(const Warnings& warnings);

}  // namespace insitu
