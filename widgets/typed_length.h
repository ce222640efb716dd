// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Lengths the user types from a tape measure, converted between m, cm and mm as decimal text, not
// by multiplying doubles: "7" cm becomes the decimal 0.07 m and then the nearest double to it,
// which is the double "0.07" typed in metres gives (7 * 0.01 would give 0.07000000000000001). So a
// reference typed in any of the three units is the same reference, bit for bit.

#include <QString>
#include <optional>

#include "sonargrid/base/length_unit.h"

namespace sg::ui {

// The value of `text` (a decimal number typed in `typed`, e.g. "12.5", "-3", "1e3"; a comma is
// taken for the decimal point) in `stored`: the double nearest to the exact decimal. nullopt when
// the text is not a finite number.
std::optional<double> parseTypedLength(const QString& text, LengthUnit typed, LengthUnit stored);

// `value` (held in `stored`) as decimal text in `shown`: its shortest round-trip form in `stored`
// with the decimal point moved, e.g. 0.07 m shown in cm is "7". Reading the text back with
// parseTypedLength(text, shown, stored) gives `value` again.
QString typedLengthText(double value, LengthUnit stored, LengthUnit shown);

// `value` rounded to `digits` significant digits first (for offsets, whose subtraction leaves
// traces like 0.7299999999999999), then as typedLengthText.
QString roundedLengthText(double value, LengthUnit stored, LengthUnit shown, int digits = 12);

// The multiple of `cellMetres` nearest to `worldMetres`, in `stored`, computed as decimal text as
// if the user had typed it (0.05 m cells: 3 cells is 0.15, not 3 * 0.05 = 0.15000000000000002).
double snappedToCells(double worldMetres, double cellMetres, LengthUnit stored);

}  // namespace sg::ui
