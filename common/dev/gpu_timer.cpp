#include "gpu_timer.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace lab::dev {
namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

double ticks_to_ms(uint64_t begin, uint64_t end, uint32_t valid_bits, double period_ns) {
    const uint64_t mask = valid_bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << valid_bits) - 1;
    return double((end - begin) & mask) * period_ns * 1e-6;  // unsigned: wraps modulo 2^64 first
}

std::string pass_key(std::string_view name) {
    std::string key;
    for (char c : name) {
        if (std::isalnum(static_cast<unsigned char>(c)))
            key += char(std::tolower(static_cast<unsigned char>(c)));
        else if (!key.empty() && key.back() != '_')
            key += '_';
    }
    while (!key.empty() && key.back() == '_') key.pop_back();
    return key;
}

GpuPassTimer::GpuPassTimer(const VulkanContext& vk, bool on, bool keep_all) : vk_(vk), on_(on), keep_all_(keep_all) {
    // 0 valid bits: the queue has no timestamps (or --dev-without-feature timestamps).
    valid_bits_ = vk.timestamp_valid_bits();
    period_ns_ = vk.properties().limits.timestampPeriod;
    if (!on_) return;
    if (!supported()) {
        std::fprintf(stderr, "GPU time: this device has no timestamps (%s)\n", vk.properties().deviceName);
        return;
    }
    for (Slot& slot : slots_) {
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = 2 * kMaxPasses;  // a begin and an end per pass
        VkQueryPool pool = VK_NULL_HANDLE;
        VK_CHECK(vkCreateQueryPool(vk.device(), &info, nullptr, &pool));
        slot.pool = Handle<VkQueryPool>(pool, [device = vk.device()](VkQueryPool p) { vkDestroyQueryPool(device, p, nullptr); });
        slot.names.reserve(kMaxPasses);
    }
}

GpuPassTimer::~GpuPassTimer() = default;

void GpuPassTimer::begin_frame(VkCommandBuffer cmd, uint32_t slot_index) {
    if (!on()) return;
    Slot& slot = slots_[slot_index % slots_.size()];
    if (slot.pending) read(slot);  // the caller waited for the slot's fence: the results are there
    vkCmdResetQueryPool(cmd, slot.pool, 0, 2 * kMaxPasses);
    slot.names.clear();
    slot.frame = frames_++;
    slot.pending = true;
    current_ = &slot;
}

int GpuPassTimer::begin(VkCommandBuffer cmd, std::string_view name) {
    if (!on() || !current_) return -1;
    Slot& slot = *current_;
    if (slot.names.size() == kMaxPasses) {
        if (!said_too_many_)
            std::fprintf(stderr, "GPU time: more than %u passes in a frame; the rest are not timed\n", kMaxPasses);
        said_too_many_ = true;
        return -1;
    }
    const uint32_t pass = uint32_t(slot.names.size());
    slot.names.emplace_back(name);
    // A timestamp is latched once every command before it has completed the stage it names. At
    // TOP_OF_PIPE that is once they have *started*: a GPU still finishing the previous pass would
    // stamp this one's start inside it, and the passes' times would overlap (their sum could pass
    // the frame's span). At BOTTOM_OF_PIPE (every stage) it is once all earlier work is done, so
    // the pass's time is what it adds to the frame after everything before it, and no two passes'
    // times overlap. (A pass of ours may have begun earlier, overlapping the one before; that part
    // is counted in the earlier pass's time.)
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, slot.pool, 2 * pass);
    return int(pass);
}

void GpuPassTimer::end(VkCommandBuffer cmd, int pass) {
    if (!current_ || pass < 0) return;
    // Once every command before it (the pass's own included) has completed.
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, current_->pool, 2 * uint32_t(pass) + 1);
}

void GpuPassTimer::collect() {
    if (!on()) return;
    // Oldest first, so the frames stay in order.
    std::array<Slot*, RenderTarget::kFramesInFlight> pending{};
    size_t n = 0;
    for (Slot& slot : slots_)
        if (slot.pending) pending[n++] = &slot;
    std::sort(pending.begin(), pending.begin() + n, [](const Slot* a, const Slot* b) { return a->frame < b->frame; });
    for (size_t i = 0; i < n; ++i) read(*pending[i]);
    current_ = nullptr;
}

void GpuPassTimer::read(Slot& slot) {
    slot.pending = false;
    const uint32_t queries = 2 * uint32_t(slot.names.size());
    if (queries == 0) return;
    // Each query: its value and its availability (nonzero once written). The slot's fence has
    // signalled, so every query recorded is written; one that is not (a frame whose commands were
    // never submitted) makes the frame count for nothing, never a wrong number.
    std::vector<uint64_t> data(2 * size_t(queries));
    const VkResult result = vkGetQueryPoolResults(vk_.device(), slot.pool, 0, queries, data.size() * sizeof(uint64_t),
                                                  data.data(), 2 * sizeof(uint64_t),
                                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
    if (result != VK_SUCCESS && result != VK_NOT_READY) VK_CHECK(result);
    for (uint32_t q = 0; q < queries; ++q)
        if (data[2 * q + 1] == 0) return;
    const auto stamp = [&](uint32_t q) { return data[2 * size_t(q)]; };

    FrameGpuTimes times;
    times.frame = slot.frame;
    for (uint32_t pass = 0; pass < slot.names.size(); ++pass) {
        const double ms = ticks_to_ms(stamp(2 * pass), stamp(2 * pass + 1), valid_bits_, period_ns_);
        const auto same = std::find_if(times.passes.begin(), times.passes.end(),
                                       [&](const PassTime& p) { return p.name == slot.names[pass]; });
        if (same != times.passes.end())
            same->ms += ms;
        else
            times.passes.push_back({slot.names[pass], ms});
    }
    times.span_ms = ticks_to_ms(stamp(0), stamp(queries - 1), valid_bits_, period_ns_);
    done_.push_back(std::move(times));
    if (!keep_all_ && done_.size() > kRecentFrames) done_.pop_front();
}

std::vector<PassTime> GpuPassTimer::recent_medians() const {
    if (done_.empty()) return {};
    std::vector<PassTime> shown = done_.back().passes;
    const size_t first = done_.size() > kRecentFrames ? done_.size() - kRecentFrames : 0;
    for (PassTime& pass : shown) {
        std::vector<double> values;
        for (size_t f = first; f < done_.size(); ++f)
            for (const PassTime& p : done_[f].passes)
                if (p.name == pass.name) values.push_back(p.ms);
        pass.ms = median(std::move(values));
    }
    return shown;
}

bool GpuPassTimer::print(const std::string& lab, uint64_t first, uint64_t count) const {
    const auto timed = [&](const FrameGpuTimes& frame) { return frame.frame >= first && frame.frame - first < count; };
    std::vector<std::string> names;  // every pass seen, in order of first appearance
    std::vector<double> sums, spans;
    for (const FrameGpuTimes& frame : done_) {
        if (!timed(frame)) continue;
        double sum = 0.0;
        for (const PassTime& p : frame.passes) {
            sum += p.ms;
            if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
        }
        sums.push_back(sum);
        spans.push_back(frame.span_ms);
    }
    if (sums.empty()) return false;
    std::printf("gpu_passes lab=%s frames=%zu", lab.c_str(), sums.size());
    for (const std::string& name : names) {
        std::vector<double> values;  // the frames that had the pass (a static map is drawn once)
        for (const FrameGpuTimes& frame : done_)
            if (timed(frame))
                for (const PassTime& p : frame.passes)
                    if (p.name == name) values.push_back(p.ms);
        std::printf(" %s_ms=%.3f", pass_key(name).c_str(), median(std::move(values)));
    }
    std::printf(" sum_ms=%.3f total_ms=%.3f\n", median(sums), median(spans));
    std::fflush(stdout);
    return true;
}

}  // namespace lab::dev
