// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/base/length_unit.h"

namespace sg {

const char* lengthUnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::Metre:
      return "m";
    case LengthUnit::Centimetre:
      return "cm";
    case LengthUnit::Millimetre:
      return "mm";
  }
  return "m";
}

std::optional<LengthUnit> lengthUnitFromName(const std::string& name) {
  if (name == "m") return LengthUnit::Metre;
  if (name == "cm") return LengthUnit::Centimetre;
  if (name == "mm") return LengthUnit::Millimetre;
  return std::nullopt;
}

double metresPerUnit(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::Metre:
      return 1.0;
    case LengthUnit::Centimetre:
      return 0.01;
    case LengthUnit::Millimetre:
      return 0.001;
  }
  return 1.0;
}

}  // namespace sg
