// vraster itself: Renderer::fill per item into a vraster::Image, the calls svg::render makes; optionally with the
// renderer's threads (Renderer::set_threads: the frame's fills are queued and drawn by flush()).
#include <string>

#include "engines.hpp"
#include "vraster/renderer.hpp"

namespace bench {
namespace {

class VrasterEngine final : public Engine {
 public:
  explicit VrasterEngine(int threads) : name_(threads > 1 ? "vraster-" + std::to_string(threads) + "t" : "vraster") {
    renderer_.set_threads(threads);
  }
  const char* name() const override { return name_.c_str(); }
  std::string version() const override { return "vraster (this tree)"; }

  void prepare(const vraster::svg::Document& doc) override {
    doc_ = &doc;
    image_ = vraster::Image(doc.width, doc.height);
  }

  bool frame() override {
    image_.clear(vraster::Color{1, 1, 1, 1});
    const vraster::svg::RenderSettings settings;  // what svg::render uses by default (but the bench's tolerance)
    for (const vraster::svg::DrawItem& item : doc_->items) {
      if (!item.is_fill()) continue;  // the fill benchmark compares fills only
      const vraster::FillOptions options{settings.rule_override.value_or(item.rule), settings.aa, tolerance_};
      renderer_.fill(image_, item.path, item.transform, item.color, options);
    }
    renderer_.flush();  // with threads the fills were queued: the frame is drawn here
    return true;
  }

  vraster::Image image() const override { return image_; }

 private:
  std::string name_;
  const vraster::svg::Document* doc_ = nullptr;
  vraster::Image image_;
  vraster::Renderer renderer_;
};

}  // namespace

std::unique_ptr<Engine> make_vraster_engine(int threads) { return std::make_unique<VrasterEngine>(threads); }

}  // namespace bench
