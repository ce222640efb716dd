// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The CSV a sweep writes (docs/sweeps.md, "The CSV"): '#' comment lines that identify the sweep
// (a fingerprint of everything that decides its rows, the shard, the number of sets), one header
// line, then one row per finished set in set order: its index, every declared parameter and every
// metric asked for. Rows are appended and flushed one by one, so a file cut short by Ctrl-C holds
// only whole rows and a rerun resumes after its last one; `sweep-merge` joins shards by the same
// reader.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sonargrid/sweep/set_evaluation.h"

namespace sg::cli {

// ---- the metrics a sweep can ask for (--metric)

// Canonical names in column order: vsdns, derivative, entropy, two-run, then the reference metrics
// of `score` (iop, correlation, ...). Each text may be a comma-separated list; "path" stands for
// both path metrics. Duplicates are dropped. Throws UsageError naming an unknown metric.
std::vector<std::string> parseSweepMetrics(const std::vector<std::string>& texts);
bool isReferenceMetric(const std::string& name);
// The CSV columns of the metrics (the JSON keys of `score --json` and `goodness --json`).
std::vector<std::string> metricColumns(const std::vector<std::string>& metrics);
SetMeasures measuresOf(const std::vector<std::string>& metrics);
// One value per column of metricColumns(); empty where the metric is undefined for this map.
std::vector<std::optional<double>> metricValues(const std::vector<std::string>& metrics,
                                                const SetEvaluation& evaluation);

// ---- header and rows

struct SweepHeader {
  // Identity fields, in order: two sweeps are the same when all of these are equal. The
  // fingerprint is a hash of them.
  std::vector<std::pair<std::string, std::string>> fields;
  // Informational fields (the paths the files were read from): not compared.
  std::vector<std::pair<std::string, std::string>> notes;
  std::size_t shardIndex = 0;
  std::size_t shardCount = 1;
  std::size_t sets = 0;  // of the whole sweep
  std::vector<std::string> metrics;
  std::vector<std::string> parameters;  // declared names, in declaration order
  std::vector<std::string> columns;     // metricColumns(metrics)

  std::string fingerprint() const;  // 16 hex digits
  std::string text() const;         // the comment lines and the column header line
  // The first identity field that differs, as "KEY: this A, that B"; empty when the same.
  std::string difference(const SweepHeader& other) const;
};

struct SweepCsvRow {
  std::size_t index = 0;
  std::vector<double> parameters;
  std::vector<std::optional<double>> values;
};
std::string rowText(const SweepCsvRow& row);

struct SweepCsv {
  SweepHeader header;
  std::vector<SweepCsvRow> rows;
  std::size_t wholeBytes = 0;  // bytes up to the end of the last whole line
  bool cutLine = false;        // the file ends in a partial line (a kill mid-write)
};

// Throws InputError naming the file and line for a file that is not a sweep CSV or is malformed.
SweepCsv readSweepCsv(const std::string& path);

// The set indices of one shard: i with i mod count == index, ascending.
std::vector<std::size_t> shardIndices(std::size_t sets, std::size_t index, std::size_t count);

// FNV-1a 64 of a file's bytes, as 16 hex digits; InputError naming the file when unreadable.
std::string fileHash(const std::string& path);

}  // namespace sg::cli
