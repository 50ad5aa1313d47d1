// Looking up check_scene's findings by code, for tests of `check`.
#pragma once

#include <string>

#include "soundpaint/check.h"

namespace sp::test {

// The finding with `code`, or nullptr when check reported none.
inline const CheckFinding* find_finding(const CheckReport& report, const std::string& code) {
  for (const CheckFinding& f : report.findings)
    if (f.code == code) return &f;
  return nullptr;
}

}  // namespace sp::test
