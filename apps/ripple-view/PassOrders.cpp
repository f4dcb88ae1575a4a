// PassOrder on the wire (see PassOrders.h): a fixed record of plain fields, so that one broadcast carries it.
#include "apps/ripple-view/PassOrders.h"

#include <cstring>
#include <type_traits>

namespace ripple::apps {
namespace {

enum : uint32_t { kHasView = 1, kHasSettings = 2, kHasSize = 4, kHasScale = 8 };

struct PassOrderRecord {
    uint32_t quit = 0, moving = 0, maxSamples = 0, has = 0;
    // CameraView (its name stays on rank 0: it names nothing the device sees)
    uint32_t orthographic = 0;
    float position[3] = {}, direction[3] = {}, up[3] = {};
    float fovy = 0.0f, height = 0.0f, apertureRadius = 0.0f, focusDistance = 0.0f;
    // ViewerSettings
    int32_t pixelSamples = 0, maxPathLength = 0;
    float background[4] = {};
    float ambientRadiance = 0.0f;
    uint32_t quickLookWhileMoving = 0;
    int32_t display = 0;
    uint32_t size[2] = {};
    uint32_t reducedScale = 0;
};
static_assert(std::is_trivially_copyable_v<PassOrderRecord>);

PassOrderRecord recordOf(const PassOrder& order) {
    PassOrderRecord r;
    r.quit = order.quit;
    r.moving = order.moving;
    r.maxSamples = order.maxSamples;
    const PendingChanges& c = order.changes;
    if (c.view) {
        r.has |= kHasView;
        r.orthographic = c.view->orthographic;
        std::memcpy(r.position, &c.view->position.x, sizeof r.position);
        std::memcpy(r.direction, &c.view->direction.x, sizeof r.direction);
        std::memcpy(r.up, &c.view->up.x, sizeof r.up);
        r.fovy = c.view->fovy;
        r.height = c.view->height;
        r.apertureRadius = c.view->apertureRadius;
        r.focusDistance = c.view->focusDistance;
    }
    if (c.settings) {
        r.has |= kHasSettings;
        r.pixelSamples = c.settings->pixelSamples;
        r.maxPathLength = c.settings->maxPathLength;
        std::memcpy(r.background, &c.settings->background.x, sizeof r.background);
        r.ambientRadiance = c.settings->ambientRadiance;
        r.quickLookWhileMoving = c.settings->quickLookWhileMoving;
        r.display = int32_t(c.settings->display);
    }
    if (c.size) {
        r.has |= kHasSize;
        r.size[0] = c.size->x;
        r.size[1] = c.size->y;
    }
    if (c.reducedScale) {
        r.has |= kHasScale;
        r.reducedScale = *c.reducedScale;
    }
    return r;
}

PassOrder orderOf(const PassOrderRecord& r) {
    PassOrder order;
    order.quit = r.quit != 0;
    order.moving = r.moving != 0;
    order.maxSamples = r.maxSamples;
    PendingChanges& c = order.changes;
    if (r.has & kHasView) {
        CameraView view;
        view.orthographic = r.orthographic != 0;
        std::memcpy(&view.position.x, r.position, sizeof r.position);
        std::memcpy(&view.direction.x, r.direction, sizeof r.direction);
        std::memcpy(&view.up.x, r.up, sizeof r.up);
        view.fovy = r.fovy;
        view.height = r.height;
        view.apertureRadius = r.apertureRadius;
        view.focusDistance = r.focusDistance;
        c.view = view;
    }
    if (r.has & kHasSettings) {
        ViewerSettings settings;
        settings.pixelSamples = r.pixelSamples;
        settings.maxPathLength = r.maxPathLength;
        std::memcpy(&settings.background.x, r.background, sizeof r.background);
        settings.ambientRadiance = r.ambientRadiance;
        settings.quickLookWhileMoving = r.quickLookWhileMoving != 0;
        settings.display = DisplayChannel(r.display);
        c.settings = settings;
    }
    if (r.has & kHasSize) c.size = glm::uvec2(r.size[0], r.size[1]);
    if (r.has & kHasScale) c.reducedScale = r.reducedScale;
    return order;
}

}  // namespace

PassOrder sharePassOrder(const mpi::Communicator& ranks, const PassOrder& order) {
    if (!ranks.distributed()) return order;
    PassOrderRecord record = recordOf(order);
    ranks.broadcast(std::span<uint8_t>(reinterpret_cast<uint8_t*>(&record), sizeof record));
    return orderOf(record);
}

bool shareStart(const mpi::Communicator& ranks, bool started) {
    uint8_t flag = started ? 1 : 0;
    ranks.broadcast(std::span<uint8_t>(&flag, 1));
    return flag != 0;
}

}  // namespace ripple::apps
