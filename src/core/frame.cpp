#include "core/frame.h"

namespace core {

const char* clog_end_name(ClogEnd e) {
  switch (e) {
    case ClogEnd::Spontaneous:
      return "spontaneous";
    case ClogEnd::Vibration:
      return "vibration";
    case ClogEnd::Rule:
      return "rule";
    case ClogEnd::RunEnd:
      return "run_end";
  }
  return "unknown";
}

}  // namespace core
