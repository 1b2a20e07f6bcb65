#pragma once
// Results in the layout of Honeybee's daylight-factor recipe, which its tools (and Pollination's
// viewers) read back onto the model: a folder with one `<grid>.res` per grid, one DF in percent
// per line in the grid's sensor order, and `grids_info.json` listing the grids in order with their
// sensor counts (name, identifier, count, group, full_id, start_ln, as Honeybee writes it).

#include <string>
#include <vector>

#include "report/reports.hpp"
#include "report/staged_output.hpp"

namespace daylit::cli {

// Stages the files in `folder` (which must exist): nothing appears unless the run commits.
// Refined sensors are not written (the .res parallels the model's grid).
void stage_honeybee_results(StagedOutputs& outputs, const std::string& folder, const std::vector<GridReport>& reports);

}  // namespace daylit::cli
