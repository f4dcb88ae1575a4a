// PassOrder on the wire (see PassOrders.h): a fixed record of plain fields, so that one broadcast carries it.
#include "apps/ripple-view/PassOrders.h"

#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace ripple::apps {
namespace {

enum : uint32_t { kHasView = 1, kHasSettings = 2, kHasSize = 4, kHasScale = 8 };

struct PassOrderRecord {
    uint32_t quit = 0, moving = 0, has = 0;
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
    uint64_t fieldEditBytes = 0;        // the bytes of PassOrder::fieldEdits, broadcast next
};
static_assert(std::is_trivially_copyable_v<PassOrderRecord>);

PassOrderRecord recordOf(const PassOrder& order) {
    PassOrderRecord r;
    r.quit = order.quit;
    r.moving = order.moving;
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
    r.fieldEditBytes = order.fieldEdits.size();
    return r;
}

PassOrder orderOf(const PassOrderRecord& r) {
    PassOrder order;
    order.quit = r.quit != 0;
    order.moving = r.moving != 0;
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

std::vector<uint8_t> encodePassOrder(const PassOrder& order) {
    const PassOrderRecord record = recordOf(order);
    const auto* bytes = reinterpret_cast<const uint8_t*>(&record);
    return std::vector<uint8_t>(bytes, bytes + sizeof record);
}

PassOrder decodePassOrder(const std::vector<uint8_t>& bytes) {
    if (bytes.size() != sizeof(PassOrderRecord)) throw std::runtime_error("a pass order of the wrong size");
    PassOrderRecord record;
    std::memcpy(&record, bytes.data(), sizeof record);
    PassOrder order = orderOf(record);
    order.fieldEdits.resize(record.fieldEditBytes);  // filled by the broadcast that follows
    return order;
}

PassOrder sharePassOrder(const mpi::Communicator& ranks, const PassOrder& order) {
    if (!ranks.distributed()) return order;
    std::vector<uint8_t> fixed = encodePassOrder(order);
    ranks.broadcast(fixed);
    PassOrder shared = decodePassOrder(fixed);
    if (ranks.rank() == 0) shared.fieldEdits = order.fieldEdits;
    ranks.broadcast(shared.fieldEdits);
    return shared;
}

namespace {

class Writer {
public:
    template <class T>
    void put(const T& value) {
        const auto* bytes = reinterpret_cast<const uint8_t*>(&value);
        out.insert(out.end(), bytes, bytes + sizeof(T));
    }
    template <class T>
    void putAll(const std::vector<T>& values) {
        put(uint64_t(values.size()));
        for (const T& v : values) put(v);
    }
    std::vector<uint8_t> out;
};

class Reader {
public:
    explicit Reader(const std::vector<uint8_t>& bytes) : bytes_(bytes) {}
    template <class T>
    T get() {
        if (bytes_.size() - at_ < sizeof(T)) throw std::runtime_error("rank 0's field edits end early");
        T value;
        std::memcpy(&value, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return value;
    }
    template <class T>
    std::vector<T> getAll() {
        const uint64_t count = get<uint64_t>();
        if (count > (bytes_.size() - at_) / sizeof(T)) throw std::runtime_error("rank 0's field edits end early");
        std::vector<T> values(count);
        for (T& v : values) v = get<T>();
        return values;
    }

private:
    const std::vector<uint8_t>& bytes_;
    size_t at_ = 0;
};

}  // namespace

std::vector<uint8_t> encodeFieldEdits(const SceneEdits& edits, const SceneEditRequests& requests) {
    Writer w;
    w.put(uint64_t(requests.volumes.size()));
    for (size_t i : requests.volumes) {
        const EditableVolume& v = edits.volumes.at(i);
        w.put(uint64_t(i));
        w.putAll(v.colors);
        w.putAll(v.opacities);
        w.put(v.valueRange);
        w.put(v.unitDistance);
    }
    w.put(uint64_t(requests.isosurfaces.size()));
    for (size_t i : requests.isosurfaces) {
        w.put(uint64_t(i));
        w.put(edits.isosurfaces.at(i).isovalue);
    }
    return w.out;
}

SceneEditRequests decodeFieldEdits(const std::vector<uint8_t>& bytes, SceneEdits& edits) {
    SceneEditRequests requests;
    Reader r(bytes);
    for (uint64_t n = r.get<uint64_t>(); n > 0; --n) {
        const uint64_t i = r.get<uint64_t>();
        if (i >= edits.volumes.size()) throw std::runtime_error("rank 0 edited a volume this rank does not have");
        EditableVolume& v = edits.volumes[i];
        v.colors = r.getAll<glm::vec3>();
        v.opacities = r.getAll<float>();
        v.valueRange = r.get<glm::vec2>();
        v.unitDistance = r.get<float>();
        requests.volumes.insert(i);
    }
    for (uint64_t n = r.get<uint64_t>(); n > 0; --n) {
        const uint64_t i = r.get<uint64_t>();
        if (i >= edits.isosurfaces.size()) throw std::runtime_error("rank 0 edited an iso-surface this rank does not have");
        edits.isosurfaces[i].isovalue = r.get<float>();
        requests.isosurfaces.insert(i);
    }
    return requests;
}

bool shareStart(const mpi::Communicator& ranks, bool started) {
    uint8_t flag = started ? 1 : 0;
    ranks.broadcast(std::span<uint8_t>(&flag, 1));
    return flag != 0;
}

}  // namespace ripple::apps
