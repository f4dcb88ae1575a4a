// The robustness matrix's quick sweep: every case must render finite pixels, and hold its stated
// tolerance wherever its precision argument says it should (Robustness.h). A group with no rows fails.
#include "apps/ripple-robustness/Robustness.h"

#include <doctest/doctest.h>

namespace ripple::robustness {
namespace {

void checkGroup(std::vector<Row> (*run)(Harness&, bool)) {
    Harness harness;
    const std::vector<Row> rows = run(harness, true);
    CHECK(!rows.empty());
    for (const Row& row : rows) {
        INFO(row.group << " / " << row.name << ": " << row.measured << " (" << row.why << ")");
        CHECK(row.finite);
        CHECK((row.holds || !row.expected));
    }
    // Validation runs inside the device, which reports what it says as an error.
    CHECK(harness.validationMessages() == 0);
}

}  // namespace

TEST_CASE("robustness: precision (scale x translation white furnace)") { checkGroup(precisionCases); }
TEST_CASE("robustness: intersection (acne, coincident, thin, degenerate, edges)") { checkGroup(intersectionCases); }
TEST_CASE("robustness: radiometry (1e-10..1e10, tiny emitters, sun)") { checkGroup(radiometryCases); }
TEST_CASE("robustness: sizes (frames, samples, fields of view, cameras)") { checkGroup(extremeSizeCases); }
TEST_CASE("robustness: bad data (NaN/Inf, indices, element types)") { checkGroup(badDataCases); }
TEST_CASE("robustness: API misuse (overflowing sizes, releases, stale handles, freed memory)") {
    checkGroup(misuseCases);
}

}  // namespace ripple::robustness
