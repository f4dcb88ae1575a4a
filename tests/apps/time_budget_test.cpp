// ripple-render's --time decisions (TimeBudget.h) on made-up frame times: the first frame ends the start-up,
// later frames start only while the longest recent one still fits, and a start-up past the limit stops at once.
#include "apps/ripple-render/TimeBudget.h"

#include <doctest/doctest.h>

using ripple::apps::TimeBudget;

TEST_CASE("TimeBudget: the first frame ends the start-up and always runs") {
    TimeBudget budget(2.0, TimeBudget::Clock::now());
    CHECK(budget.nextFrameFits(5.0));  // even past the limit: an image must come out
    budget.frameEnded(0.4, 1.5);
    CHECK(budget.startUpSeconds() == doctest::Approx(1.5));
    CHECK(budget.firstFrameBegin() == doctest::Approx(0.4));
    CHECK(budget.firstFrameSeconds() == doctest::Approx(1.1));
    CHECK_FALSE(budget.startUpExceeded());
    CHECK(budget.predictedFrame() == 0.0);  // the first frame, with its pipelines, predicts nothing
    CHECK(budget.nextFrameFits(1.5));
    CHECK_FALSE(budget.nextFrameFits(2.0));
}

TEST_CASE("TimeBudget: a frame starts only when the longest of the last four still ends within the limit") {
    TimeBudget budget(2.0, TimeBudget::Clock::now());
    budget.frameEnded(0.3, 1.0);
    budget.frameEnded(1.0, 1.3);   // 0.3 s
    budget.frameEnded(1.3, 1.4);   // 0.1 s
    CHECK(budget.predictedFrame() == doctest::Approx(0.3));
    CHECK(budget.nextFrameFits(1.65));
    CHECK_FALSE(budget.nextFrameFits(1.75));
    budget.frameEnded(1.4, 1.5);
    budget.frameEnded(1.5, 1.6);
    budget.frameEnded(1.6, 1.7);   // the 0.3 s frame is no longer among the last four
    CHECK(budget.predictedFrame() == doctest::Approx(0.1));
    CHECK(budget.longestFrame() == doctest::Approx(0.3));
    CHECK(budget.nextFrameFits(1.85));
    CHECK_FALSE(budget.nextFrameFits(1.95));
}

TEST_CASE("TimeBudget: a start-up past the limit leaves the first frame alone") {
    TimeBudget budget(1.0, TimeBudget::Clock::now());
    budget.frameEnded(0.5, 1.2);
    CHECK(budget.startUpExceeded());
    CHECK_FALSE(budget.nextFrameFits(1.2));
}

TEST_CASE("TimeBudget without a limit only measures") {
    TimeBudget budget(std::nullopt, TimeBudget::Clock::now());
    budget.frameEnded(0.5, 100.0);
    budget.frameEnded(100.0, 200.0);
    CHECK_FALSE(budget.startUpExceeded());
    CHECK(budget.nextFrameFits(1e9));
    CHECK(budget.elapsed() >= 0.0);
}
