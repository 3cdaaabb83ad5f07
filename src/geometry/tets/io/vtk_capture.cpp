#include "geometry/tets/io/vtk_capture.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <vector>

namespace zs::detail {

namespace {

// Strip VTK's location prefix and fold the message onto one line.
std::string clean_message(const std::string& raw) {
  std::string s = raw;
  // "ERROR: In /path/x.cxx, line 12\nClass (0x1234): text" -> "text"
  // Also "Warning: In ..." and "Generic Warning: In ...".
  const auto nl = s.find('\n');
  const auto in = s.find(": In ");
  if (nl != std::string::npos && in != std::string::npos && in < nl && s.find(", line ", in) < nl)
    s = s.substr(nl + 1);
  auto tag = s.find("): ");
  if (tag != std::string::npos && s.find(" (", 0) < tag) s = s.substr(tag + 3);
  // Fold whitespace; binary junk VTK echoes from a garbage file becomes '?'.
  std::string out;
  bool space = false;
  for (char c : s) {
    if (c == '\n' || c == '\r' || c == '\t' || c == ' ') {
      space = !out.empty();
      continue;
    }
    if (space) out.push_back(' ');
    space = false;
    const auto u = static_cast<unsigned char>(c);
    out.push_back(u < 0x20 || u >= 0x7f ? '?' : c);
  }
  constexpr size_t kMax = 240;
  if (out.size() > kMax) out = out.substr(0, kMax) + "...";
  return out;
}

class CaptureWindow : public vtkOutputWindow {
 public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow);

  std::vector<std::string> errors;
  std::vector<std::string> warnings;

  void DisplayText(const char*) override {}
  void DisplayErrorText(const char* t) override { errors.push_back(clean_message(t ? t : "")); }
  void DisplayWarningText(const char* t) override { warnings.push_back(clean_message(t ? t : "")); }
  void DisplayGenericWarningText(const char* t) override {
    warnings.push_back(clean_message(t ? t : ""));
  }
  void DisplayDebugText(const char*) override {}

 protected:
  CaptureWindow() = default;
};
vtkStandardNewMacro(CaptureWindow);

}  // namespace

struct VtkMessageCapture::Impl {
  vtkSmartPointer<vtkOutputWindow> previous;
  vtkSmartPointer<CaptureWindow> window;
  vtkSmartPointer<vtkCallbackCommand> observer;
  vtkLogger::Verbosity stderr_verbosity = vtkLogger::VERBOSITY_OFF;
};

static void on_event(vtkObject*, unsigned long event, void* client, void* call) {
  auto* w = static_cast<CaptureWindow*>(client);
  std::string msg = clean_message(call ? static_cast<const char*>(call) : "unknown VTK message");
  (event == vtkCommand::ErrorEvent ? w->errors : w->warnings).push_back(msg);
}

VtkMessageCapture::VtkMessageCapture() : impl_(std::make_unique<Impl>()) {
  // VTK 9 also logs every error through vtkLogger straight to stderr, even
  // when an observer handles it; mute that too. There is no getter for the
  // stderr level, but with no log callbacks/files the cutoff equals it.
  impl_->stderr_verbosity = vtkLogger::GetCurrentVerbosityCutoff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  impl_->previous = vtkOutputWindow::GetInstance();
  impl_->window = vtkSmartPointer<CaptureWindow>::New();
  vtkOutputWindow::SetInstance(impl_->window);
  impl_->observer = vtkSmartPointer<vtkCallbackCommand>::New();
  impl_->observer->SetCallback(on_event);
  impl_->observer->SetClientData(impl_->window.Get());
}

VtkMessageCapture::~VtkMessageCapture() {
  vtkOutputWindow::SetInstance(impl_->previous);
  vtkLogger::SetStderrVerbosity(impl_->stderr_verbosity);
}

void VtkMessageCapture::watch(vtkObject* obj) {
  obj->AddObserver(vtkCommand::ErrorEvent, impl_->observer);
  obj->AddObserver(vtkCommand::WarningEvent, impl_->observer);
}

std::string VtkMessageCapture::first_warning() const {
  for (const auto& w : impl_->window->warnings)
    if (!w.empty()) return w;
  return "";
}

bool VtkMessageCapture::has_error() const { return !impl_->window->errors.empty(); }

std::string VtkMessageCapture::first_error() const {
  for (const auto& e : impl_->window->errors)
    if (!e.empty()) return e;
  return has_error() ? "unknown VTK error" : "";
}

}  // namespace zs::detail
