// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "arguments.h"
#include "sonargrid/sweep/sweep_grid.h"
#include "sonargrid/sweep/sweep_metrics.h"

namespace sg::cli {
namespace {

constexpr const char* kMagic = "# sonargrid-cli sweep 1";

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 1469598103934665603ULL) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

std::string hex16(std::uint64_t v) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(v));
  return buffer;
}

bool readDouble(const std::string& t, double& v) {
  const char* end = t.data() + t.size();
  const auto [ptr, ec] = std::from_chars(t.data(), end, v);
  return !t.empty() && ec == std::errc() && ptr == end;
}

bool readSize(const std::string& t, std::size_t& v) {
  const char* end = t.data() + t.size();
  const auto [ptr, ec] = std::from_chars(t.data(), end, v);
  return !t.empty() && ec == std::errc() && ptr == end;
}

}  // namespace

// The metric grammar is the core's (sonargrid/sweep/sweep_metrics.h), shared with the app's sweep
// view; here its errors become usage errors.
std::vector<std::string> parseSweepMetrics(const std::vector<std::string>& texts) {
  try {
    return sg::parseSweepMetrics(texts);
  } catch (const SweepSpecError& e) {
    throw UsageError(e.what());
  }
}

bool isReferenceMetric(const std::string& name) {
  return sg::isReferenceMetric(name);
}

std::vector<std::string> metricColumns(const std::vector<std::string>& metrics) {
  return sg::metricColumns(metrics);
}

SetMeasures measuresOf(const std::vector<std::string>& metrics) {
  return sg::measuresOf(metrics);
}

std::vector<std::optional<double>> metricValues(const std::vector<std::string>& metrics,
                                                const SetEvaluation& e) {
  return sg::metricValues(metrics, e);
}

std::string SweepHeader::fingerprint() const {
  std::uint64_t h = fnv1a("sonargrid sweep\n");
  for (const auto& [key, value] : fields) h = fnv1a(key + ": " + value + "\n", h);
  return hex16(h);
}

std::string SweepHeader::text() const {
  std::string t = std::string(kMagic) + "\n";
  t += "# fingerprint: " + fingerprint() + "\n";
  t += "# shard: " + std::to_string(shardIndex) + "/" + std::to_string(shardCount) + "\n";
  t += "# sets: " + std::to_string(sets) + "\n";
  for (const auto& [key, value] : fields) t += "# " + key + ": " + value + "\n";
  for (const auto& [key, value] : notes) t += "# note " + key + ": " + value + "\n";
  t += "index";
  for (const std::string& p : parameters) t += "," + p;
  for (const std::string& c : columns) t += "," + c;
  return t + "\n";
}

std::string SweepHeader::difference(const SweepHeader& other) const {
  const std::size_t n = std::max(fields.size(), other.fields.size());
  for (std::size_t i = 0; i < n; ++i) {
    const std::string key = i < fields.size() ? fields[i].first : other.fields[i].first;
    const std::string a = i < fields.size() ? fields[i].second : "(none)";
    const std::string b = i < other.fields.size() ? other.fields[i].second : "(none)";
    const std::string otherKey = i < other.fields.size() ? other.fields[i].first : key;
    if (key != otherKey) return key + " / " + otherKey + ": the files describe different sweeps";
    if (a != b) return key + ": '" + a + "' against '" + b + "'";
  }
  return {};
}

std::string rowText(const SweepCsvRow& row) {
  std::string t = std::to_string(row.index);
  for (double p : row.parameters) t += "," + shortestText(p);
  for (const std::optional<double>& v : row.values) t += "," + (v ? shortestText(*v) : "");
  return t + "\n";
}

SweepCsv readSweepCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read '" + path + "'");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  SweepCsv csv;
  std::size_t lineNo = 0;
  std::size_t pos = 0;
  bool columnsRead = false;
  bool shardRead = false, setsRead = false, fingerprintRead = false;
  std::string fingerprint;
  auto fail = [&](const std::string& what) {
    throw InputError(path + ":" + std::to_string(lineNo) + ": " + what);
  };
  while (pos < bytes.size()) {
    const std::size_t eol = bytes.find('\n', pos);
    ++lineNo;
    if (eol == std::string::npos) {
      // A line without its newline: cut off by a kill mid-write. The rows before it stand.
      if (!columnsRead) fail("the header ends early (is the file cut short?)");
      csv.cutLine = true;
      break;
    }
    const std::string line = bytes.substr(pos, eol - pos);
    pos = eol + 1;
    if (lineNo == 1) {
      if (line != kMagic)
        fail("not a sonargrid sweep CSV (the first line is not '" + std::string(kMagic) + "')");
      continue;
    }
    if (!columnsRead && line.rfind("# ", 0) == 0) {
      const auto colon = line.find(": ");
      if (colon == std::string::npos) fail("a header comment without 'KEY: VALUE'");
      const std::string key = line.substr(2, colon - 2);
      const std::string value = line.substr(colon + 2);
      if (key == "fingerprint") {
        fingerprint = value;
        fingerprintRead = true;
      } else if (key == "shard") {
        const auto slash = value.find('/');
        if (slash == std::string::npos ||
            !readSize(value.substr(0, slash), csv.header.shardIndex) ||
            !readSize(value.substr(slash + 1), csv.header.shardCount) ||
            csv.header.shardCount == 0 || csv.header.shardIndex >= csv.header.shardCount)
          fail("shard must read I/N, got '" + value + "'");
        shardRead = true;
      } else if (key == "sets") {
        if (!readSize(value, csv.header.sets)) fail("sets must be a whole number");
        setsRead = true;
      } else if (key.rfind("note ", 0) == 0) {
        csv.header.notes.emplace_back(key.substr(5), value);
      } else {
        csv.header.fields.emplace_back(key, value);
        if (key == "metrics") {
          csv.header.metrics = value.empty() ? std::vector<std::string>{} : splitCommas(value);
          try {
            if (parseSweepMetrics(csv.header.metrics) != csv.header.metrics)
              fail("metrics '" + value + "' are not in canonical order");
          } catch (const UsageError& e) {
            fail(e.what());
          }
        }
      }
      continue;
    }
    if (!columnsRead) {
      if (!fingerprintRead || !shardRead || !setsRead)
        fail("the header lacks its fingerprint, shard or sets line");
      if (fingerprint != csv.header.fingerprint())
        fail("the fingerprint does not match the header's fields (was the header edited?)");
      csv.header.columns = metricColumns(csv.header.metrics);
      const std::vector<std::string> names = splitCommas(line);
      if (names.empty() || names.front() != "index") fail("the column header must start 'index'");
      if (names.size() < 1 + csv.header.columns.size())
        fail("the column header lacks the metrics' columns");
      const std::size_t nParameters = names.size() - 1 - csv.header.columns.size();
      for (std::size_t i = 0; i < csv.header.columns.size(); ++i) {
        if (names[1 + nParameters + i] != csv.header.columns[i])
          fail("column " + std::to_string(2 + nParameters + i) + " should be '" +
               csv.header.columns[i] + "', got '" + names[1 + nParameters + i] + "'");
      }
      csv.header.parameters.assign(names.begin() + 1,
                                   names.begin() + 1 + static_cast<std::ptrdiff_t>(nParameters));
      columnsRead = true;
      csv.wholeBytes = pos;
      continue;
    }
    const std::vector<std::string> cells = splitCommas(line);
    const std::size_t want = 1 + csv.header.parameters.size() + csv.header.columns.size();
    if (cells.size() != want)
      fail(std::to_string(cells.size()) + " fields, expected " + std::to_string(want));
    SweepCsvRow row;
    if (!readSize(cells[0], row.index) || row.index >= csv.header.sets)
      fail("index '" + cells[0] + "' is not a set of this sweep");
    for (std::size_t i = 0; i < csv.header.parameters.size(); ++i) {
      double v = 0;
      if (!readDouble(cells[1 + i], v))
        fail(csv.header.parameters[i] + ": '" + cells[1 + i] + "' is not a number");
      row.parameters.push_back(v);
    }
    for (std::size_t i = 0; i < csv.header.columns.size(); ++i) {
      const std::string& c = cells[1 + csv.header.parameters.size() + i];
      double v = 0;
      if (c.empty()) {
        row.values.emplace_back();
      } else if (readDouble(c, v)) {
        row.values.emplace_back(v);
      } else {
        fail(csv.header.columns[i] + ": '" + c + "' is not a number");
      }
    }
    if (row.index % csv.header.shardCount != csv.header.shardIndex)
      fail("set " + cells[0] + " does not belong to shard " +
           std::to_string(csv.header.shardIndex) + "/" + std::to_string(csv.header.shardCount));
    if (!csv.rows.empty() && row.index <= csv.rows.back().index)
      fail("set " + cells[0] + " is out of order or repeated");
    csv.rows.push_back(std::move(row));
    csv.wholeBytes = pos;
  }
  if (!columnsRead) {
    lineNo = std::max<std::size_t>(lineNo, 1);
    fail("the header ends early (no column line)");
  }
  return csv;
}

std::vector<std::size_t> shardIndices(std::size_t sets, std::size_t index, std::size_t count) {
  std::vector<std::size_t> out;
  for (std::size_t i = index; i < sets; i += count) out.push_back(i);
  return out;
}

std::string fileHash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read '" + path + "'");
  std::uint64_t h = 1469598103934665603ULL;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    h = fnv1a(std::string_view(buffer, static_cast<std::size_t>(in.gcount())), h);
  }
  return hex16(h);
}

}  // namespace sg::cli
