// Presents scores of one or more runs: the paper's table as text, JSON for
// scripts, and a PNG plot of the position error over time.
#pragma once

#include <string>
#include <vector>

#include "tools/eval/evaluation.hpp"

namespace slamer {

struct NamedRun {
  std::string name;
  RunScores scores;
};

std::string render_table(const std::vector<NamedRun>& runs, const EvalOptions& options);
std::string render_json(const std::vector<NamedRun>& runs, const EvalOptions& options);
// Writes the plot; throws std::runtime_error if the file cannot be written.
void write_error_plot(const std::vector<NamedRun>& runs, const std::string& png_path);

}  // namespace slamer
