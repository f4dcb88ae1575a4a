// What every object of one Ripple device shares: the status callback, the Vulkan context (created on
// first use, so API-only use never touches Vulkan), and the stamp counter that orders changes.
#pragma once

#include "anari/anari.h"
#include "anari/device/object/HandleTable.h"
#include "core/render/RayExchange.h"
#include "mpi/Communicator.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

namespace ripple::vk {
class Context;
struct ContextOptions;
}  // namespace ripple::vk
namespace ripple::core { enum class Traversal; }  // core/render/Traversal.h

namespace ripple::device {

class Object;

class DeviceState {
public:
    DeviceState(ANARIDevice handle, ANARIStatusCallback callback, const void* callbackUserPtr);
    ~DeviceState();

    ANARIDevice handle() const { return handle_; }
    // The application may replace the callback with the device parameters "statusCallback" and
    // "statusCallbackUserData".
    void setStatusCallback(ANARIStatusCallback callback, const void* userPtr);
    // Thread-safe (frames render on worker threads). source may be null for device-level messages.
    void report(const Object* source, ANARIStatusSeverity severity, ANARIStatusCode code,
                const std::string& message) const;

    // Monotonic stamp for change tracking (Object::lastCommitted, array unmaps).
    uint64_t nextStamp() { return ++stamp_; }
    uint64_t nextSerial() { return ++serial_; }

    // The Vulkan context all frames render with; created on first call (throws vk::VulkanError).
    vk::Context& vulkan();
    // The device parameter "discreteMemory" (vk::ContextOptions::discreteMemory; unset defers to
    // RIPPLE_VK_DISCRETE_MEMORY). Read when the context is created: false, and nothing changes, once it exists.
    bool setDiscreteMemory(bool on);
    // The context if a render created it already, else null (properties report on it without creating it).
    const vk::Context* vulkanIfCreated();
    // The device parameter "vulkanDevice": a device index or name substring (vk::ContextOptions::deviceOverride),
    // which beats RIPPLE_VK_DEVICE and the node-local rank's choice. Read when the context is created: false,
    // and nothing changes, once it exists.
    bool setVulkanDevice(const std::string& choice);
    // The device property "ripple.vulkanDevices": one line per Vulkan device (index, name, kind, driver),
    // the one this device renders with (or would, before its first render) marked "[chosen]". Under MPI its
    // first use may make the communicator, which is collective: every rank asks. Valid until the next call
    // or the device's release.
    const char* vulkanDevicesText();

    // Frames render on worker threads that use this state: the device waits for them before it goes,
    // even for frames the application never released.
    void beginWork();
    void endWork();
    void waitForWork();
    bool idle();

    // Data-parallel rendering: the ranks this device renders with. The application may give its own
    // communicator (device parameter mpiCommunicator / pointer_to_mpi_communicator, or a frame's
    // mpiCommunicator) before the first collective call; otherwise MPI_COMM_WORLD when MPI is running.
    // Created on first use, which is always inside a collective call; with it this rank's place among the
    // ranks on its node (mpi::Communicator::nodeRanks, collective too), which picks its GPU when the Vulkan
    // context is made: that comes after, at the first render.
    void setCommunicatorHandle(const void* mpiComm);
    const mpi::Communicator& communicator();
    // The device parameter "traversal" (core::Traversal; Auto when unset, which defers to
    // RIPPLE_TRAVERSAL): what the frames' tracers and scenes are built for.
    void setTraversal(core::Traversal traversal) { traversal_ = traversal; }
    core::Traversal traversal() const { return traversal_.load(); }
    // The device parameter "rayExchange" (core::ExchangeKind; Bounds when unset): how data-parallel frames
    // send rays between ranks. Every rank must set the same (frames check it).
    void setRayExchange(core::ExchangeKind kind) { rayExchange_ = kind; }
    core::ExchangeKind rayExchange() const { return rayExchange_.load(); }
    // Creation order of frames and worlds: data-parallel ANARI identifies them by it across ranks.
    uint64_t nextFrameIndex() { return frames_++; }
    uint64_t nextWorldIndex() { return worlds_++; }

    // Every live object's handle (not the device's); its count is the leak report at device release.
    HandleTable handles;

private:
    vk::ContextOptions contextOptions() const;  // from the parameters and node ranks; vulkanMutex_ held

    ANARIDevice handle_;
    ANARIStatusCallback callback_;
    const void* callbackUserPtr_;
    mutable std::mutex reportMutex_;
    std::atomic<uint64_t> stamp_{0};
    std::atomic<uint64_t> serial_{0};
    std::mutex workMutex_;
    std::condition_variable workDone_;
    int workInFlight_ = 0;
    std::mutex vulkanMutex_;
    std::unique_ptr<vk::Context> vulkan_;
    std::optional<bool> discreteMemory_;  // guarded by vulkanMutex_, as the three below
    std::string vulkanDevice_;
    std::optional<mpi::Communicator::NodeRanks> nodeRanks_;
    std::string vulkanDevicesText_;
    std::shared_ptr<const void> communicatorHandle_;  // a copy of the application's MPI_Comm
    std::unique_ptr<mpi::Communicator> communicator_;
    std::atomic<uint64_t> frames_{0};
    std::atomic<uint64_t> worlds_{0};
    std::atomic<core::Traversal> traversal_{};  // Auto
    std::atomic<core::ExchangeKind> rayExchange_{};  // Bounds
};

}  // namespace ripple::device
