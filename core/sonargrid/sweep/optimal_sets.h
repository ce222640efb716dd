// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How paper 002 picks "the optimal parameter set" from a sweep (§5), each rule with the paragraph
// that defines it:
//
// First approach, mean of standard deviations (VSDNS), three rules:
//  - lowest histogram bin: "After generating a histogram for 1440 VSDNS with 14 bins ... the lowest
//    bin of the histogram denotes the optimal parameter set. ... we find all maps and parameter
//    sets responsible for this interval. Thus, the average of individual parameter over these
//    parameter sets denote the optimal parameter set" (Table 1, 5th column; Table 2 lists that
//    bin);
//  - minimum: "if we consider the minimum VSDNS instead of the average, the obtained parameter set
//    is 6th column of the table" — the set with the smallest VSDNS;
//  - mean: "if we consider VSDNS-bar instead of using histogram ... although this is a crude
//    method", and the caption: "7th col is obtained by taking the arithmetic mean over 1440 VSDNS".
//    The 7th column is one point of the grid (P5 = 14, 2·P3 = 2.0), not an average of parameters,
//    so the rule reads: the set whose VSDNS is nearest the mean of all VSDNS values.
// Second approach, derivative of maps: "The map containing the lowest noise is the best one" — the
//    set with the smallest D_map (the sum; the maps of one sweep share one grid, so the paper's
//    normalisation for maps "different in sizes" is not needed).
// Third approach, two runs: "The optimum parameter set is the one that gets the maximum positive
//    score and minimum negative score" — read as the largest positive − negative, ties broken by
//    the fewer disagreeing cells.
//
// Ties go to the earliest set in sweep order. A set whose measure is undefined (no VSDNS, no
// scored cell) takes no part.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "sonargrid/params/parameters.h"
#include "sonargrid/sweep/parameter_sweep.h"

namespace sg {

inline constexpr int kPaper002HistogramBins = 14;  // paper 002 §5, Figure 7

// Equal-width bins from the smallest to the largest defined value (as MATLAB's hist(y, 14), the
// paper's Figure 7): bin k holds min + k·w ≤ v < min + (k+1)·w with w = (max − min)/bins, the last
// bin also holds max. All values equal (w = 0): every value in bin 0.
struct Histogram {
  double min = 0.0;
  double max = 0.0;
  double width = 0.0;
  std::vector<std::size_t> counts;  // `bins` entries
  std::vector<int> binOf;           // per value; -1 for an undefined value
  double lowerEdge(int bin) const { return min + bin * width; }
  double upperEdge(int bin) const;  // max for the last bin, exactly
};

// Throws std::invalid_argument when bins < 1 or no value is defined.
Histogram histogramOf(std::span<const std::optional<double>> values,
                      int bins = kPaper002HistogramBins);

struct OptimalSet {
  ParameterSet parameters;           // the chosen set, or the average of `members`
  std::vector<std::size_t> members;  // indices into the sweep: one, or the whole lowest bin
  double criterion = 0.0;            // the value the rule looked at (see each rule)
};

// Every numeric parameter averaged over `members` (lowest-bin rule); a whole-number parameter
// takes the members' value nearest that mean (the first member's on a tie), never a value that
// was not swept. Throws std::invalid_argument on an empty list.
ParameterSet averageParameters(const std::vector<ParameterSet>& sets,
                               const std::vector<std::size_t>& members);

// criterion: the largest VSDNS in the lowest bin. Throws std::invalid_argument when `values` and
// `sets` differ in size or no value is defined (as every rule below).
OptimalSet lowestBinAverage(std::span<const std::optional<double>> values,
                            const std::vector<ParameterSet>& sets,
                            int bins = kPaper002HistogramBins);
// criterion: the minimum VSDNS.
OptimalSet minimumVsdns(std::span<const std::optional<double>> values,
                        const std::vector<ParameterSet>& sets);
// criterion: the mean VSDNS over every defined value.
OptimalSet nearestMeanVsdns(std::span<const std::optional<double>> values,
                            const std::vector<ParameterSet>& sets);
// criterion: the smallest D_map among rows with a scored cell.
OptimalSet minimumDerivativeNoise(const std::vector<SweepRow>& rows,
                                  const std::vector<ParameterSet>& sets);
// criterion: positive − negative of the best row. Throws std::invalid_argument when no row has a
// two-run comparison.
OptimalSet bestTwoRunAgreement(const std::vector<SweepRow>& rows,
                               const std::vector<ParameterSet>& sets);

}  // namespace sg
