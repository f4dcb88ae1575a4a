// Status reporting and the lazily created Vulkan context shared by the objects of one device.
#include "anari/device/object/DeviceState.h"

#include "anari/device/object/Object.h"
#include "core/vk/Context.h"

#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

namespace ripple::device {

DeviceState::DeviceState(ANARIDevice handle, ANARIStatusCallback callback, const void* callbackUserPtr)
    : handle_(handle), callback_(callback), callbackUserPtr_(callbackUserPtr) {}

DeviceState::~DeviceState() = default;

void DeviceState::setStatusCallback(ANARIStatusCallback callback, const void* userPtr) {
    std::lock_guard lock(reportMutex_);
    callback_ = callback;
    callbackUserPtr_ = userPtr;
}

void DeviceState::report(const Object* source, ANARIStatusSeverity severity, ANARIStatusCode code,
                         const std::string& message) const {
    std::lock_guard lock(reportMutex_);
    if (!callback_) return;
    callback_(callbackUserPtr_, handle_, source ? source->handle() : nullptr, source ? source->type() : ANARI_DEVICE, severity, code,
              message.c_str());
}

void DeviceState::beginWork() {
    std::lock_guard lock(workMutex_);
    ++workInFlight_;
}

void DeviceState::endWork() {
    std::lock_guard lock(workMutex_);
    if (--workInFlight_ == 0) workDone_.notify_all();
}

void DeviceState::waitForWork() {
    std::unique_lock lock(workMutex_);
    workDone_.wait(lock, [this] { return workInFlight_ == 0; });
}

bool DeviceState::idle() {
    std::lock_guard lock(workMutex_);
    return workInFlight_ == 0;
}

void DeviceState::setCommunicatorHandle(const void* mpiComm) {
    if (communicator_) {
        report(nullptr, ANARI_SEVERITY_WARNING, ANARI_STATUS_INVALID_OPERATION,
               "mpiCommunicator set after the first data-parallel call; the device keeps its communicator");
        return;
    }
    communicatorHandle_ = mpi::Communicator::copyHandle(mpiComm);
}

const mpi::Communicator& DeviceState::communicator() {
    if (!communicator_) {
        auto made = std::make_unique<mpi::Communicator>(mpi::Communicator::fromHandle(communicatorHandle_.get()));
        const mpi::Communicator::NodeRanks node = made->nodeRanks();
        std::lock_guard lock(vulkanMutex_);
        nodeRanks_ = node;
        communicator_ = std::move(made);
    }
    return *communicator_;
}

vk::ContextOptions DeviceState::contextOptions() const {
    // RIPPLE_VK_VALIDATION=1 turns the Khronos validation layer on (the tests do).
    vk::ContextOptions options;
    const char* validation = std::getenv("RIPPLE_VK_VALIDATION");
    options.validation = validation && std::string(validation) == "1";
    options.discreteMemory = discreteMemory_;
    options.deviceOverride = vulkanDevice_;
    options.deviceOverrideSource = "the device parameter vulkanDevice";
    if (nodeRanks_) {
        options.localRank = static_cast<uint32_t>(nodeRanks_->rank);
        options.localRankCount = static_cast<uint32_t>(nodeRanks_->size);
    }
    return options;
}

vk::Context& DeviceState::vulkan() {
    std::lock_guard lock(vulkanMutex_);
    if (!vulkan_) vulkan_ = std::make_unique<vk::Context>(contextOptions());
    return *vulkan_;
}

bool DeviceState::setVulkanDevice(const std::string& choice) {
    std::lock_guard lock(vulkanMutex_);
    if (vulkan_) return false;
    vulkanDevice_ = choice;
    return true;
}

const char* DeviceState::vulkanDevicesText() {
    if (mpi::mpiActive()) communicator();  // knows this rank's place on its node
    std::lock_guard lock(vulkanMutex_);
    const std::vector<vk::DeviceDescription> devices = vk::listDevices();
    std::string chosenLine;
    std::optional<uint32_t> chosen;
    if (vulkan_) {
        chosen = vulkan_->deviceIndex();
    } else {
        try {
            const vk::DeviceChoice choice = vk::chooseDevice(devices, contextOptions());
            chosen = choice.index;
            if (!choice.reason.empty()) chosenLine = choice.reason;
        } catch (const std::exception& error) {
            chosenLine = std::string("no device would be chosen: ") + error.what();
        }
    }
    std::string text;
    for (uint32_t i = 0; i < devices.size(); ++i)
        text += std::to_string(i) + ": " + devices[i].name + " (" + vk::deviceTypeName(devices[i].type) + "), driver " +
                devices[i].driver + (chosen == i ? " [chosen]" : "") + "\n";
    if (devices.empty()) text += "no Vulkan device\n";
    if (!chosenLine.empty()) text += chosenLine + "\n";
    vulkanDevicesText_ = text;
    return vulkanDevicesText_.c_str();
}

const vk::Context* DeviceState::vulkanIfCreated() {
    std::lock_guard lock(vulkanMutex_);
    return vulkan_.get();
}

bool DeviceState::setDiscreteMemory(bool on) {
    std::lock_guard lock(vulkanMutex_);
    if (vulkan_) return false;
    discreteMemory_ = on;
    return true;
}

}  // namespace ripple::device
