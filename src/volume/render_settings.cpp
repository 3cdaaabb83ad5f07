#include "volume/render_settings.h"

namespace zs {

const char* to_string(ScanStrategy s) {
  switch (s) {
    case ScanStrategy::BBox: return "bbox";
    case ScanStrategy::BConvert: return "bconvert";
    case ScanStrategy::Span: return "span";
  }
  return "?";
}

bool parse_scan_strategy(const std::string& s, ScanStrategy* out) {
  for (ScanStrategy k : {ScanStrategy::BBox, ScanStrategy::BConvert, ScanStrategy::Span})
    if (s == to_string(k)) return *out = k, true;
  return false;
}

}  // namespace zs
