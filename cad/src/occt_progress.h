#pragma once
// OpenCASCADE's progress indicator forwarding to the request's callback, at most every 1%.

#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressScope.hxx>

#include "occt_shape.h"

namespace conform::cad {

class ProgressIndicator : public Message_ProgressIndicator {
 public:
  ProgressIndicator(const ProgressSink& sink, const char* stage) : sink_(sink), stage_(stage) {}

 protected:
  void Show(const Message_ProgressScope& /*scope*/, const Standard_Boolean force) override {
    const double position = GetPosition();
    if (!force && position < last_ + 0.01) return;
    last_ = position;
    sink_(stage_, position);
  }

 private:
  ProgressSink sink_;
  const char* stage_;
  double last_ = -1.0;
};

}  // namespace conform::cad
