#include "cli/option_checks.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include <fmt/format.h>

namespace railvsi::cli {

CLI::Validator finite_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v)) return "'" + text + "' is not a number";
        if (!std::isfinite(v) || v < lo || v > hi)
          return fmt::format("{} is out of range: give a finite number from {} to {}", text, lo, hi);
        return {};
      },
      fmt::format("FLOAT in [{} - {}]", lo, hi));
}

CLI::Validator one_word() {
  return CLI::Validator(
      [](const std::string& v) {
        if (v.empty()) return std::string("must not be empty");
        return std::any_of(v.begin(), v.end(), [](unsigned char c) { return c <= ' ' || c == 0x7f; })
                   ? std::string("must be one word (no blanks or control characters)")
                   : std::string();
      },
      "WORD");
}

CLI::Validator kubernetes_quantity() {
  return CLI::Validator(
      [](const std::string& v) {
        // Kubernetes' quantity grammar: a decimal number, then a binary
        // (Ki..Ei) or decimal (n u m k M G T P E) suffix or an exponent.
        static const std::regex grammar(R"(^\+?([0-9]+(\.[0-9]*)?|\.[0-9]+)(Ki|Mi|Gi|Ti|Pi|Ei|[numkMGTPE]|[eE][+-]?[0-9]+)?$)");
        std::smatch m;
        if (!std::regex_match(v, m, grammar))
          return fmt::format("'{}' is not a Kubernetes quantity (e.g. 2Gi, 1500Mi, 3e9)", v);
        if (m.str(1).find_first_of("123456789") == std::string::npos)
          return fmt::format("'{}' is zero: give a quantity above zero", v);
        return std::string();
      },
      "QUANTITY");
}

CLI::Validator kubernetes_name() {
  return CLI::Validator(
      [](const std::string& v) {
        static const std::regex grammar(R"(^[a-z0-9]([-a-z0-9]*[a-z0-9])?(\.[a-z0-9]([-a-z0-9]*[a-z0-9])?)*$)");
        if (v.size() > 253 || !std::regex_match(v, grammar))
          return fmt::format("'{}' is not a Kubernetes object name (lower-case letters, digits, '-' and '.', "
                             "starting and ending with a letter or digit)",
                             v);
        return std::string();
      },
      "NAME");
}

}  // namespace railvsi::cli
