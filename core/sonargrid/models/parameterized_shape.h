// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The parameterized model's per-reading shape (paper 002 §4, Figure 4 and eq 7; the model itself
// is models/parameterized.cpp). In a header so that the batched sweep (sweep/batch_evaluation.cpp)
// evaluates the very same formula, operation for operation, for many parameter sets at once.

#include <cmath>
#include <limits>

#include "sonargrid/models/cone_model.h"

namespace sg {

// Per reading; S is double for evaluate() and float for the footprint (cone_model.h).
template <class S>
struct ParameterizedShape {
  S emptyBelow;  // Region II: r < s − P3; everywhere without an echo
  S halfAngle;   // P5 in radians
  S invHalfAngle;
  S emptySlope;  // (0.5 − P2 − P1) / (s − P3)
  S s, p1, p4;
  S tentSlope;  // (P4 − 0.5 − P2) / P3

  template <class T>
  [[gnu::always_inline]] ConeValue<T> value(T r, T a) const {
    const auto empty = r < emptyBelow;
    // Region II rises from P1; Region I is a tent, 0.5 + P2 at |r − s| = P3 and P4 at r = s.
    const T axis = empty ? p1 + emptySlope * r : p4 - tentSlope * lanes::abs(r - s);
    const T p = (halfAngle - a) * invHalfAngle * (axis - S(0.5)) + S(0.5);  // eq 7
    const auto high = p > S(0.5);                                           // fromProbability
    return {!empty, empty, high ? T{} : S(1) - S(2) * p, high ? S(2) * p - S(1) : T{}, p};
  }
};

template <class S>
ConeBeam<ParameterizedShape<S>> prepareParameterized(double range, double maxRange, double p1,
                                                     double p2, double p3, double p4, double p5,
                                                     bool noEchoFree) {
  ConeBeam<ParameterizedShape<S>> b;
  const bool echo = std::isfinite(range);
  if (!echo && !noEchoFree) return b;
  b.active = true;
  b.halfAngle = p5;
  const double emptyEnd = echo ? range - p3 : maxRange;
  b.reach = echo ? range + p3 : maxRange;
  ParameterizedShape<S>& m = b.shape;
  // r < x is r < the float x rounds up to, for a float r.
  m.emptyBelow = roundUp<S>(echo ? emptyEnd : std::numeric_limits<double>::infinity());
  m.halfAngle = S(p5);
  m.invHalfAngle = S(1.0 / p5);
  m.emptySlope = S(emptyEnd > 0.0 ? (0.5 - p2 - p1) / emptyEnd : 0.0);
  m.s = S(echo ? range : maxRange);
  m.p1 = S(p1);
  m.p4 = S(p4);
  m.tentSlope = S((p4 - 0.5 - p2) / p3);
  return b;
}

}  // namespace sg
