// The --time decisions of TimeBudget.h: when the start-up ends and whether the next frame fits.
#include "apps/ripple-render/TimeBudget.h"

#include <algorithm>

namespace ripple::apps {

void TimeBudget::frameEnded(double begin, double end) {
    if (frames_++ == 0) {
        firstFrameBegin_ = begin;
        startUpEnd_ = end;
        return;
    }
    const double seconds = end - begin;
    recent_[frames_ % recent_.size()] = seconds;
    longest_ = std::max(longest_, seconds);
}

double TimeBudget::predictedFrame() const {
    return *std::max_element(recent_.begin(), recent_.end());
}

bool TimeBudget::nextFrameFits(double now) const {
    if (!limit_ || frames_ == 0) return true;
    if (startUpExceeded()) return false;
    return now + predictedFrame() < *limit_;
}

}  // namespace ripple::apps
