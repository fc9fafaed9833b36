// SPDX-License-Identifier: Apache-2.0
// The adversarial input values of the stress suites: classes of values written into one role of an
// otherwise plausible frame (NaN, +-Inf, -1e30..1e30, +-FLT_MAX, denormals, zeros, fireflies, and
// the values only some roles can have wrong: zero or >1 albedo, zero-length and non-unit normals,
// depth 0 / negative / 1e10, motion off-screen and huge).
#pragma once

#include "stress_util.h"

#include <string>
#include <vector>

namespace stress {

/// One case: which role gets which class of values.
struct AdversarialCase {
    std::string role;
    std::string values;
    std::string name() const { return role + "/" + values; }
};

/// Every case: the generic classes for every input role, then the role-specific ones.
std::vector<AdversarialCase> adversarialCases();

/// Write the case's values into `frame` (which holds every role).
void applyCase(const AdversarialCase& c, FrameData& frame);

} // namespace stress
