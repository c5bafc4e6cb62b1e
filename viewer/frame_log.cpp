#include "frame_log.h"

#include <algorithm>

#include "core/frame/median.h"
#include "vulkan/check.h"

namespace photon::viewer {
namespace {

constexpr std::uint32_t kMarks = 4;

}  // namespace

PassTimer::PassTimer(const vk::Context& context) : context_(context) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = kMarks;
    VK_CHECK(vkCreateQueryPool(context.device, &info, nullptr, &pool_));
}

PassTimer::~PassTimer() {
    vkDeviceWaitIdle(context_.device);
    vkDestroyQueryPool(context_.device, pool_, nullptr);
}

void PassTimer::reset(VkCommandBuffer cmd) {
    if (context_.timestampValidBits > 0) {
        vkCmdResetQueryPool(cmd, pool_, 0, kMarks);
    }
}

void PassTimer::mark(VkCommandBuffer cmd, std::uint32_t index) {
    if (context_.timestampValidBits > 0) {
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, index);
    }
}

PassTimes PassTimer::read() {
    PassTimes times;
    if (context_.timestampValidBits == 0) {
        return times;
    }
    std::uint64_t ticks[kMarks] = {};
    VK_CHECK(vkGetQueryPoolResults(context_.device, pool_, 0, kMarks, sizeof(ticks), ticks, sizeof(std::uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    std::uint64_t mask = context_.timestampValidBits >= 64 ? ~0ull : (1ull << context_.timestampValidBits) - 1;
    double msPerTick = double(context_.properties.limits.timestampPeriod) * 1e-6;
    auto ms = [&](std::uint32_t i) { return double((ticks[i + 1] - ticks[i]) & mask) * msPerTick; };
    times.dots = ms(0);
    times.display = ms(1);
    times.hud = ms(2);
    return times;
}

void FrameLog::add(const FrameRecord& record) { records_.push_back(record); }

double FrameLog::fps() const {
    double seconds = 0.0;
    std::size_t frames = 0;
    for (auto it = records_.rbegin(); it != records_.rend() && seconds < 0.5; ++it) {
        seconds += it->loopMs * 1e-3;
        frames += 1;
    }
    return seconds > 0.0 ? double(frames) / seconds : 0.0;
}

FrameRecord FrameLog::median(std::size_t skip) const {
    std::size_t first = std::min(skip, records_.size() > 1 ? records_.size() - 1 : 0);
    auto column = [&](auto get) {
        std::vector<double> v;
        for (std::size_t i = first; i < records_.size(); ++i) {
            v.push_back(get(records_[i]));
        }
        return photon::median(v);
    };
    FrameRecord m;
    m.loopMs = column([](const FrameRecord& r) { return r.loopMs; });
    for (const StageInfo& s : kStages) {
        m.stages[s.id] = column([&](const FrameRecord& r) { return r.stages[s.id]; });
    }
    m.passes.dots = column([](const FrameRecord& r) { return r.passes.dots; });
    m.passes.display = column([](const FrameRecord& r) { return r.passes.display; });
    m.passes.hud = column([](const FrameRecord& r) { return r.passes.hud; });
    m.photonsPerSecond = column([](const FrameRecord& r) { return r.photonsPerSecond; });
    return m;
}

}  // namespace photon::viewer
