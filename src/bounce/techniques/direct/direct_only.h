// Technique "direct": direct light only, no indirect term. The baseline every technique adds to.
#pragma once

#include "bounce/render/technique.h"

namespace bounce {

class DirectOnly final : public Technique {
 public:
  std::string name() const override { return "direct"; }
  bool has_indirect() const override { return false; }
  void indirect(const FrameContext&, Image&) override {}
};

}  // namespace bounce
