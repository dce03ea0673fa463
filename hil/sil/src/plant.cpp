#include "cvtplant/sil/harness/plant.hpp"

namespace cvt::sil::harness {

LoopbackBridgePlant::LoopbackBridgePlant(InProcessBus& bus, std::int64_t frame_cost_ns)
    : bus_(bus), bridge_(std::make_unique<Bridge>(bus.plant_node(), bus.clock)), frame_cost_ns_(frame_cost_ns) {
  bridge_->load_scene(*cvt::find_builtin_scene("tip-in"));
}

std::function<void()> LoopbackBridgePlant::idle() {
  return [this] { bridge_->service(0); };
}

RealTimeBus LoopbackBridgePlant::realtime() {
  return RealTimeBus{bus_.clock, [this] { deadline_ = bus_.clock.now_ns() + bridge_->frame_ns(); },
                     [this] {
                       bus_.clock.sleep_until(deadline_);
                       bridge_->realtime_frame();
                       bus_.clock.advance(frame_cost_ns_);
                       deadline_ += bridge_->frame_ns();
                       if (bus_.clock.now_ns() > deadline_) bridge_->note_overrun();
                     },
                     0, "virtual clock"};
}

}  // namespace cvt::sil::harness
