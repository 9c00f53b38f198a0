#pragma once
/// \file c_format.hpp
/// Number formatting in the "C" format whatever the host process's locale (a host that
/// calls setlocale(LC_ALL, "de_DE.UTF-8") or sets a comma-decimal global C++ locale must
/// not change a byte of roprec's outputs). printf-family functions, std::to_string(double) and
/// default-constructed streams follow the locale; these helpers and std::to_chars do not.

#include <locale.h>
#include <clocale>

#include <string>

namespace roprec {

/// printf("%.*f", decimals, v) in the "C" locale ("nan"/"inf" for non-finite values).
std::string cFixed(double v, int decimals);
/// printf("%.*g", precision, v) in the "C" locale.
std::string cGeneral(double v, int precision);
/// A robot card's number style: `significant` digits, trailing zeros dropped, a plain exponent
/// ("2.413e6", "8.38e4", "5").
std::string formatCardNumber(double v, int significant = 4);

/// While alive, the calling thread uses the "C" locale for the C library (printf, strtod, ...),
/// whatever the process's global locale (uselocale(3); other threads are not affected). Library
/// entry points called by hosts (C API, Python, RoboDK) should hold one.
class ClassicLocaleScope {
 public:
  ClassicLocaleScope();
  ~ClassicLocaleScope();
  ClassicLocaleScope(const ClassicLocaleScope&) = delete;
  ClassicLocaleScope& operator=(const ClassicLocaleScope&) = delete;

 private:
  locale_t previous_{nullptr};
};

}  // namespace roprec
