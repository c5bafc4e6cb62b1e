// A Device is one processor that runs the stages: the CPU's cores (cpu/), a CUDA GPU (cuda/), a
// Vulkan GPU (vulkan/). It only allocates, uploads, runs a stage, reads back and reports its
// limits; what a frame computes, and in which order, is decided by the Renderer
// (core/frame/renderer.h) and shared/. Several devices render one frame together through a
// Collective (core/frame/collective.h).
#pragma once

#include <cstdint>
#include <string>

#include "core/frame/buffers.h"
#include "core/scene/scene.h"
#include "shared/layout.h"
#include "shared/stages.h"

namespace photon {

// Milliseconds of each stage of one frame (device time on GPUs), by STAGE_*.
struct StageTimes {
    double ms[STAGE_COUNT] = {};
    double& operator[](std::uint32_t stage) { return ms[stage]; }
    double operator[](std::uint32_t stage) const { return ms[stage]; }
    double total() const {
        double sum = 0.0;
        for (double t : ms) {
            sum += t;
        }
        return sum;
    }
};

// What a device reports of the stages it ran: their times and the counters buffer.
struct FrameResult {
    StageTimes ms;
    std::uint32_t counters[COUNTER_COUNT] = {};
};

struct DeviceOptions {
    std::string device;       // Vulkan: index or part of the name; CUDA: index
    bool validation = false;  // Vulkan: enable the validation layer; any message is an error
    bool parity = false;      // CUDA: kernels without FMA contraction, bit-exact with the CPU device
};

class Device {
public:
    virtual ~Device() = default;

    virtual std::string name() const = 0;        // its backend: "cpu", "cuda", "vulkan"
    virtual std::string deviceName() const = 0;  // the processor or GPU it runs on

    // What this device may allocate now (what it holds already counts as free).
    virtual MemoryLimits memoryLimits() = 0;
    // Whether the buffers live in host memory (the CPU device): then the memory check already
    // counts the image's host copies (adjustPlan), else they are checked against host memory apart.
    virtual bool buffersInHostMemory() const { return false; }
    // Whether its stages run on the host's cores (the CPU device, Vulkan on a software device
    // such as lavapipe): the default photon count follows it (choosePhotons).
    virtual bool runsOnCpu() const { return false; }

    // Entries a device adds for its own scheduling (Vulkan: the levels of its scan in cellStart).
    virtual void adjustPlan(BufferPlan& plan, const PhotonBudget& budget) { (void)plan, (void)budget; }
    // The scene's arrays (sceneArray()) into their buffers, sized as the plan says. The scene
    // outlives the device's use of it (the Renderer keeps it).
    virtual void uploadScene(const Scene& scene, const BufferPlan& plan) = 0;
    // Every buffer that is not the scene's, sized as the plan says; contents need not be kept.
    virtual void allocate(const BufferPlan& plan, const PhotonBudget& budget, std::uint32_t width,
                          std::uint32_t height) = 0;

    // A frame, or a part of one: beginStages(), runStage() or skipStage() for each stage of
    // shared/stages.h in order, submitStages(), endStages() (which waits and returns the times
    // and counters). beginStages() clears the counters, except to `resume` a frame after a
    // collective exchange wrote them (writeBuffer()). A skipped stage keeps its place in the
    // order (timers that run from stage to stage record it as taking no time).
    virtual void beginStages(const FrameParams& params, bool resume = false) = 0;
    virtual void runStage(std::uint32_t stage, const FrameParams& params) = 0;
    virtual void skipStage(std::uint32_t stage) { (void)stage; }
    // Starts what was recorded without waiting (a GPU's queue submission); endStages() then
    // waits. Devices that run as they go do nothing here.
    virtual void submitStages() {}
    virtual FrameResult endStages() = 0;

    // `bytes` bytes of the buffer at `binding`, from byte `offset`, after every earlier frame.
    virtual void readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) = 0;
    // The same bytes written, before the next frame's stages (a collective's exchange).
    virtual void writeBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, const void* data) = 0;
};

}  // namespace photon
