// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The length units users write in their files: reference maps keep corners in the unit they were
// typed in, and CSV logs name the unit of their positions and ranges (docs/formats.md).

#include <optional>
#include <string>

namespace sg {

enum class LengthUnit { Metre, Centimetre, Millimetre };

// "m", "cm", "mm": the spelling of the JSON `units` key and of the CSV layout's length= and range=.
const char* lengthUnitName(LengthUnit unit);
std::optional<LengthUnit> lengthUnitFromName(const std::string& name);
double metresPerUnit(LengthUnit unit);

}  // namespace sg
