// SPDX-License-Identifier: GPL-3.0-or-later
#include "typed_length.h"

#include <charconv>
#include <cmath>
#include <string>

namespace sg::ui {
namespace {

// A decimal number as sign, digits (no leading zeros; "0" for zero) and a power of ten:
// value = (negative ? -1 : 1) * digits * 10^exponent.
struct Decimal {
  bool negative = false;
  std::string digits;
  int exponent = 0;
};

// Powers of ten of a metre per unit: m 10^0, cm 10^-2, mm 10^-3.
int unitExponent(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::Centimetre:
      return -2;
    case LengthUnit::Millimetre:
      return -3;
    case LengthUnit::Metre:
      break;
  }
  return 0;
}

std::optional<Decimal> parseDecimal(std::string s) {
  Decimal d;
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) d.negative = s[i++] == '-';
  bool point = false, anyDigit = false;
  int fraction = 0;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (c >= '0' && c <= '9') {
      anyDigit = true;
      if (!(d.digits.empty() && c == '0')) d.digits += c;
      if (point) ++fraction;
    } else if ((c == '.' || c == ',') && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (!anyDigit) return std::nullopt;
  int exponent = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    const auto [end, ec] = std::from_chars(s.data() + i + (i < s.size() && s[i] == '+'),
                                           s.data() + s.size(), exponent);
    if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
    i = s.size();
  }
  if (i != s.size()) return std::nullopt;
  if (d.digits.empty()) d.digits = "0";
  if (std::abs(exponent) > 100000) return std::nullopt;
  d.exponent = exponent - fraction;
  return d;
}

std::optional<double> toDouble(const Decimal& d) {
  const std::string text = (d.negative ? "-" : "") + d.digits + "e" + std::to_string(d.exponent);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

// Plain decimal notation for everyday magnitudes, scientific beyond.
QString decimalText(Decimal d) {
  while (d.digits.size() > 1 && d.digits.back() == '0') {
    d.digits.pop_back();
    ++d.exponent;
  }
  const bool zero = d.digits == "0";
  std::string out = d.negative && !zero ? "-" : "";
  const int n = static_cast<int>(d.digits.size());
  if (zero) {
    out += "0";
  } else if (d.exponent >= 0 && n + d.exponent <= 16) {
    out += d.digits + std::string(static_cast<std::size_t>(d.exponent), '0');
  } else if (d.exponent < 0 && n + d.exponent > -6) {
    const int pointAt = n + d.exponent;  // digits before the point
    if (pointAt > 0) {
      out += d.digits.substr(0, static_cast<std::size_t>(pointAt)) + "." +
             d.digits.substr(static_cast<std::size_t>(pointAt));
    } else {
      out += "0." + std::string(static_cast<std::size_t>(-pointAt), '0') + d.digits;
    }
  } else {
    out += d.digits.substr(0, 1);
    if (n > 1) out += "." + d.digits.substr(1);
    out += "e" + std::to_string(d.exponent + n - 1);
  }
  return QString::fromStdString(out);
}

Decimal shortestDecimal(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return *parseDecimal(std::string(buffer, result.ptr));
}

}  // namespace

std::optional<double> parseTypedLength(const QString& text, LengthUnit typed, LengthUnit stored) {
  auto d = parseDecimal(text.trimmed().toStdString());
  if (!d) return std::nullopt;
  d->exponent += unitExponent(typed) - unitExponent(stored);
  return toDouble(*d);
}

QString typedLengthText(double value, LengthUnit stored, LengthUnit shown) {
  if (!std::isfinite(value)) return QString::number(value);
  Decimal d = shortestDecimal(value);
  d.exponent += unitExponent(stored) - unitExponent(shown);
  return decimalText(d);
}

QString roundedLengthText(double value, LengthUnit stored, LengthUnit shown, int digits) {
  if (!std::isfinite(value)) return QString::number(value);
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value,
                                    std::chars_format::scientific, digits - 1);
  Decimal d = *parseDecimal(std::string(buffer, result.ptr));
  d.exponent += unitExponent(stored) - unitExponent(shown);
  return decimalText(d);
}

double snappedToCells(double worldMetres, double cellMetres, LengthUnit stored) {
  const double k = std::round(worldMetres / cellMetres);
  const double fallback = k * cellMetres / metresPerUnit(stored);
  if (!std::isfinite(k) || std::abs(k) > 1e9) return fallback;
  Decimal cell = shortestDecimal(cellMetres);
  cell.exponent += -unitExponent(stored);
  long long mantissa = 0;
  const auto [end, ec] =
      std::from_chars(cell.digits.data(), cell.digits.data() + cell.digits.size(), mantissa);
  long long product = 0;
  if (ec != std::errc() || __builtin_mul_overflow(mantissa, static_cast<long long>(k), &product))
    return fallback;
  Decimal d;
  d.negative = product < 0;
  d.digits = std::to_string(product < 0 ? -product : product);
  d.exponent = cell.exponent;
  return toDouble(d).value_or(fallback);
}

}  // namespace sg::ui
