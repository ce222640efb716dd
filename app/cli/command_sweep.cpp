// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli sweep` and `sonargrid-cli sweep-merge` (docs/sweeps.md): one map per parameter
// set of a grid over any declared parameters, each measured by the metrics asked for, rows
// streamed to a CSV that survives Ctrl-C and resumes; shards for job arrays, merged back row for
// row.

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <thread>

#include "commands.h"
#include "sonargrid/base/atomic_file.h"
#include "stop_signal.h"
#include "sweep_options.h"
#include "sweep_report.h"

namespace sg::cli {
namespace {

// Test-only: SONARGRID_TEST_SET_DELAY_MS=N makes every finished set wait N ms before its row is
// written, so that a test can interrupt a tiny sweep part-way (docs/sweeps.md says so). Not for
// users.
int testSetDelayMs() {
  const char* v = std::getenv("SONARGRID_TEST_SET_DELAY_MS");
  if (!v || !*v) return 0;
  return std::clamp(std::atoi(v), 0, 60000);
}

// Appends whole rows to the CSV, each in one write() (base/atomic_file.h), so that a signal at
// any moment leaves whole rows only; synced at least every second and at the end, so that a power
// cut loses at most the last second's rows (a resumed sweep computes them again).
class RowAppender {
 public:
  explicit RowAppender(const std::string& path) : file_(path, AppendFile::Start::AtEnd) {}
  ~RowAppender() {
    try {
      file_.sync();
    } catch (const FileWriteError&) {
      // Every row is written; only its durability is in doubt, and a destructor must not throw.
    }
  }
  RowAppender(const RowAppender&) = delete;
  RowAppender& operator=(const RowAppender&) = delete;
  void append(const std::string& line) {
    file_.append(line);
    const auto now = std::chrono::steady_clock::now();
    if (now - lastSync_ >= std::chrono::seconds(1)) {
      file_.sync();
      lastSync_ = now;
    }
  }

 private:
  AppendFile file_;
  std::chrono::steady_clock::time_point lastSync_ = std::chrono::steady_clock::now();
};

int exitForSignal(int signal) {
  return 128 + signal;
}

}  // namespace

int runSweepCommand(Arguments& args) {
  SweepOptions o = parseSweepOptions(args);
  const std::vector<std::string> gridTexts = args.values("--grid");
  std::pair<std::size_t, std::size_t> shard{0, 1};
  if (const auto s = args.value("--shard")) shard = parseShard(*s);
  const std::string csvPath = args.required("--csv");
  const bool json = args.flag("--json");
  const bool progress = args.flag("--progress");
  args.finish();

  const SweepSpace space = parseSweepSpace(gridTexts, o);
  const std::vector<ParameterSet>& sets = space.sets;

  SweepHeader header;
  header.sets = sets.size();
  header.shardIndex = shard.first;
  header.shardCount = shard.second;
  describeSweep(o, header);
  header.fields.insert(header.fields.end(), space.fields.begin(), space.fields.end());
  const std::vector<std::size_t> indices = shardIndices(sets.size(), shard.first, shard.second);

  // Resume: a CSV of this very sweep and shard continues after its last whole row.
  std::vector<SweepCsvRow> rows;
  const bool exists = std::filesystem::exists(csvPath) && std::filesystem::file_size(csvPath) > 0;
  if (exists) {
    SweepCsv old = readSweepCsv(csvPath);
    const std::string diff = header.difference(old.header);
    if (!diff.empty() || old.header.parameters != header.parameters)
      throw InputError(csvPath + " holds a different sweep (" +
                       (diff.empty() ? std::string("other parameters") : diff) +
                       "); remove it or choose another --csv to start this one");
    if (old.header.shardIndex != header.shardIndex || old.header.shardCount != header.shardCount ||
        old.header.sets != header.sets)
      throw InputError(csvPath + " holds shard " + std::to_string(old.header.shardIndex) + "/" +
                       std::to_string(old.header.shardCount) + " of this sweep, not " +
                       std::to_string(header.shardIndex) + "/" + std::to_string(header.shardCount));
    for (std::size_t k = 0; k < old.rows.size(); ++k) {
      if (old.rows[k].index != indices[k])
        throw InputError(csvPath + ": row " + std::to_string(k + 1) + " holds set " +
                         std::to_string(old.rows[k].index) + ", expected set " +
                         std::to_string(indices[k]) + " (rows are written in set order)");
    }
    rows = std::move(old.rows);
    if (old.cutLine || old.header.text() != header.text()) {
      // Rewrite what stands: the header as this run writes it, the whole rows, not the cut line.
      std::string bytes = header.text();
      for (const SweepCsvRow& r : rows) bytes += rowText(r);
      writeFileAtomically(csvPath, bytes);
    }
  } else {
    writeFileAtomically(csvPath, header.text());
  }
  const std::size_t resumed = rows.size();

  const auto t0 = std::chrono::steady_clock::now();
  bool complete = rows.size() == indices.size();
  int signal = 0;
  if (!complete) {
    const SweepData data = loadSweepData(o);
    const SetEvaluationInput input = data.input();
    const std::vector<std::size_t> todo(indices.begin() + static_cast<std::ptrdiff_t>(resumed),
                                        indices.end());
    RowAppender appender(csvPath);
    std::map<std::size_t, SweepCsvRow> waiting;  // finished out of order, by position in `todo`
    std::size_t nextToWrite = 0;
    const int delayMs = testSetDelayMs();
    StopOnSignal stop;
    auto finished = [&](std::size_t k, const SetEvaluation& e) {
      if (delayMs > 0) std::this_thread::sleep_for(std::chrono::milliseconds(delayMs));
      SweepCsvRow row;
      row.index = todo[k];
      for (const std::string& name : header.parameters)
        row.parameters.push_back(sets[todo[k]].get(name));
      row.values = metricValues(o.metrics, e);
      waiting.emplace(k, std::move(row));
      // Rows go out in set order: those finished ahead of an earlier set wait for it.
      while (!waiting.empty() && waiting.begin()->first == nextToWrite) {
        appender.append(rowText(waiting.begin()->second));
        rows.push_back(std::move(waiting.begin()->second));
        waiting.erase(waiting.begin());
        ++nextToWrite;
      }
      if (progress) {
        std::cerr << "\rsweep " << rows.size() << "/" << indices.size() << " sets"
                  << (header.shardCount > 1 ? " (shard " + std::to_string(header.shardIndex) + "/" +
                                                  std::to_string(header.shardCount) + ")"
                                            : std::string())
                  << std::flush;
      }
    };
    try {
      evaluateSets(input, sets, todo, finished, &stop.flag());
    } catch (const FileWriteError&) {
      throw;
    } catch (const std::exception&) {
      rethrowEvaluationError(o);
    }
    if (progress) std::cerr << '\n';
    complete = rows.size() == indices.size();
    signal = stop.signalNumber();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (!complete) {
    std::cerr << "sonargrid-cli: sweep stopped by " << (signal == SIGTERM ? "SIGTERM" : "SIGINT")
              << " after " << rows.size() << " of " << indices.size() << " sets; " << csvPath
              << " holds the finished rows; run the same command again to resume\n";
    return exitForSignal(signal == 0 ? SIGINT : signal);
  }
  if (json) {
    std::cout << sweepReport(header, rows).dump() << '\n';
  } else {
    std::cout << "sweep: " << indices.size() << " sets";
    if (header.shardCount > 1)
      std::cout << " (shard " << header.shardIndex << "/" << header.shardCount << " of "
                << header.sets << ")";
    if (resumed > 0) std::cout << ", " << resumed << " resumed from the CSV";
    std::cout << ", " << seconds << " s; wrote " << csvPath << '\n';
  }
  return 0;
}

int runSweepMerge(Arguments& args) {
  const std::string outPath = args.required("--csv");
  const bool json = args.flag("--json");
  const std::vector<std::string> inputs = args.positionals();
  args.finish();
  if (inputs.empty()) throw UsageError("sweep-merge needs the shards' CSV files");

  std::vector<SweepCsv> shards;
  for (const std::string& path : inputs) shards.push_back(readSweepCsv(path));
  const SweepHeader& first = shards.front().header;
  std::vector<bool> seen(first.shardCount, false);
  std::vector<const SweepCsvRow*> bySet(first.sets, nullptr);
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const SweepHeader& h = shards[s].header;
    const std::string diff = first.difference(h);
    if (!diff.empty() || h.parameters != first.parameters || h.sets != first.sets)
      throw InputError(inputs[s] + " is from a different sweep than " + inputs[0] + " (" +
                       (diff.empty() ? std::string("other parameters or set count") : diff) + ")");
    if (h.shardCount != first.shardCount)
      throw InputError(inputs[s] + " is shard " + std::to_string(h.shardIndex) + "/" +
                       std::to_string(h.shardCount) + " but " + inputs[0] + " is one of " +
                       std::to_string(first.shardCount) + " shards");
    if (seen[h.shardIndex])
      throw InputError(inputs[s] + ": shard " + std::to_string(h.shardIndex) + "/" +
                       std::to_string(h.shardCount) + " is given twice");
    seen[h.shardIndex] = true;
    const std::size_t want = shardIndices(h.sets, h.shardIndex, h.shardCount).size();
    if (shards[s].rows.size() != want || shards[s].cutLine)
      throw InputError(inputs[s] + ": shard " + std::to_string(h.shardIndex) + "/" +
                       std::to_string(h.shardCount) + " is unfinished (" +
                       std::to_string(shards[s].rows.size()) + " of " + std::to_string(want) +
                       " sets); rerun its sweep command to finish it");
    for (const SweepCsvRow& r : shards[s].rows) bySet[r.index] = &r;
  }
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (!seen[i])
      throw InputError("shard " + std::to_string(i) + "/" + std::to_string(first.shardCount) +
                       " is missing");
  }
  SweepHeader whole = first;
  whole.shardIndex = 0;
  whole.shardCount = 1;
  whole.notes = first.notes;
  std::vector<SweepCsvRow> rows;
  std::string bytes = whole.text();
  for (const SweepCsvRow* r : bySet) {
    rows.push_back(*r);
    bytes += rowText(*r);
  }
  writeFileAtomically(outPath, bytes);
  if (json) {
    std::cout << sweepReport(whole, rows).dump() << '\n';
  } else {
    std::cout << "sweep-merge: " << shards.size() << " shards, " << rows.size() << " sets; wrote "
              << outPath << '\n';
  }
  return 0;
}

}  // namespace sg::cli
