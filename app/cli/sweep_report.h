// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What `sweep --json` and `sweep-merge --json` print (docs/sweeps.md, "JSON"): paper 002's three
// optimal-set rules over the VSDNS column (lowest histogram bin, minimum, nearest the mean; §5,
// Table 1) when VSDNS was asked for, and the best set of every metric.

#include <nlohmann/json.hpp>

#include "sweep_csv.h"

namespace sg::cli {

// Over the rows given (a whole sweep, or the part of it a shard or an interrupted run holds).
nlohmann::ordered_json sweepReport(const SweepHeader& header, const std::vector<SweepCsvRow>& rows);

// +1 when a larger value of the column is better, -1 when a smaller one is.
int betterDirection(const std::string& column);

}  // namespace sg::cli
