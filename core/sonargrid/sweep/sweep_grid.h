// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The parameter sets of a generic sweep (docs/sweeps.md): axes written as "p=a:step:b" or
// "p=v1,v2,...", ties that derive one parameter from another ("p1=1-p4", paper 002 Table 1's
// footnote *), and the sets they span over a base set. Every value is checked against the
// parameter's declared range (parameters.h) when the sets are built, so a sweep never starts with a
// set it cannot map.

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/params/parameters.h"

namespace sg {

// A --grid, --range or --tie text that cannot be read; the message names the text and what is
// wrong (and, for a value out of range, the parameter and its declared range).
class SweepSpecError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct SweepAxis {
  std::string parameter;
  std::vector<double> values;  // in the order written (a:step:b ascending)
};

// "p=a:step:b" (a, a+step, ..., up to b within 1e-9·step; step > 0, b ≥ a) or "p=v1,v2,...".
// Decimal texts step in decimal: 0.05:0.05:0.2 gives the doubles nearest 0.05, 0.1, 0.15 and 0.2,
// not 0.05 + 2·0.05 = 0.15000000000000002. Throws SweepSpecError for a bad text, an unknown
// parameter, a value outside the parameter's declared range, more than kMaxAxisValues values, or a
// value given twice.
SweepAxis parseSweepAxis(const std::string& text, const ParameterSet& base);
inline constexpr std::size_t kMaxAxisValues = 100000;

// "p=lo:hi" with lo < hi, both inside the declared range (optimize's --range).
struct SweepRange {
  std::string parameter;
  double lo = 0.0;
  double hi = 0.0;
};
SweepRange parseSweepRange(const std::string& text, const ParameterSet& base);

// A parameter set from others, one of:  NUMBER | NAME | NUMBER-NAME | NUMBER+NAME | NUMBER*NAME
// (spaces allowed around the operator). Paper 002 needs only "1-p4"; anything more is refused.
struct SweepTie {
  std::string parameter;  // the one that is set
  double constant = 0.0;
  std::string source;  // empty for a constant
  char op = 0;         // 0 (source alone or constant), '-', '+', '*'
  double valueFor(const ParameterSet& set) const;
  std::string text() const;  // canonical, e.g. "p1=1-p4"
};
SweepTie parseSweepTie(const std::string& text, const ParameterSet& base);

// Every combination of the axes' values, the first axis outermost and the last innermost (nested
// loops in the order written), each starting from `base`, then every tie applied in order. Throws
// SweepSpecError when an axis or tie names a parameter twice, a tie's source is itself tied after
// it, a tie sets a swept parameter, the product exceeds kMaxSweepSets, or a tied value leaves its
// parameter's range (naming the set).
std::vector<ParameterSet> sweepSets(const ParameterSet& base, const std::vector<SweepAxis>& axes,
                                    const std::vector<SweepTie>& ties);
inline constexpr std::size_t kMaxSweepSets = 10000000;

// Applies the ties to one set (optimize's candidate points); SweepSpecError as sweepSets().
void applyTies(ParameterSet& set, const std::vector<SweepTie>& ties);

// The shortest text that reads back to the same double ("0.15", "1e-05").
std::string shortestText(double v);

// The comma-separated fields of a text, empty ones included ("a,,b": "a", "", "b"; "": one "").
std::vector<std::string> splitCommas(const std::string& text);

// A sweep's parameter space, as `sonargrid-cli sweep` and `goodness-study` (and the app's sweep
// view) set it up: the axes read from their texts, the sets they span with the ties, and the
// fields a sweep CSV's header records for them: ("grid", "p5=6,15") per axis and ("tie",
// "p1=1-p4") per tie, in order.
struct SweepSpace {
  std::vector<SweepAxis> axes;
  std::vector<ParameterSet> sets;
  std::vector<std::pair<std::string, std::string>> fields;
};
// A SweepSpecError of sweepSpace(): `axis` is the index of the axis text at fault, empty when the
// axes are good but do not span (a tie, the number of sets).
class SweepSpaceError : public SweepSpecError {
 public:
  SweepSpaceError(const std::string& what, std::optional<std::size_t> at)
      : SweepSpecError(what), axis(at) {}
  std::optional<std::size_t> axis;
};
// parseSweepAxis() of every text, then sweepSets(); throws SweepSpaceError with their message.
SweepSpace sweepSpace(const ParameterSet& base, const std::vector<std::string>& axisTexts,
                      const std::vector<SweepTie>& ties);

// The one grid of a sweep over two runs (the two-run comparison compares them cell for cell): the
// union of the runs' fitting grids of one cell size, both snapped to multiples of it
// (Dataset::fittingGrid), so the union is too and the runs' cells line up. Throws GridLimitError
// as GridSpec::covering() does.
GridSpec gridOverRuns(const GridSpec& first, const GridSpec& second);

}  // namespace sg
