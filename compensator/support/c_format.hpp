#pragma once
/// \file c_format.hpp
/// Number formatting in the "C" format whatever the host process's locale (a host that
/// calls setlocale(LC_ALL, "de_DE.UTF-8") or sets a comma-decimal global C++ locale must
/// not change a byte of roprec's outputs). printf-family functions, std::to_string(double) and
/// default-constructed streams follow the locale; these helpers and std::to_chars/from_chars do
/// not: roprec formats its numbers with them and sets no locale of its own (no locale_t, no
/// uselocale).

#include <string>

namespace roprec {

/// printf("%.*f", decimals, v) in the "C" locale ("nan"/"inf" for non-finite values).
std::string cFixed(double v, int decimals);
/// printf("%.*g", precision, v) in the "C" locale.
std::string cGeneral(double v, int precision);
/// A robot card's number style: `significant` digits, trailing zeros dropped, a plain exponent
/// ("2.413e6", "8.38e4", "5").
std::string formatCardNumber(double v, int significant = 4);

}  // namespace roprec
