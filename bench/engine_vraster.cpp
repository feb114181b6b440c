// vraster itself: Renderer::fill per item into a vraster::Image, the calls svg::render makes.
#include "engines.hpp"
#include "vraster/renderer.hpp"

namespace bench {
namespace {

class VrasterEngine final : public Engine {
 public:
  const char* name() const override { return "vraster"; }
  std::string version() const override { return "vraster (this tree)"; }

  void prepare(const vraster::svg::Document& doc) override {
    doc_ = &doc;
    image_ = vraster::Image(doc.width, doc.height);
  }

  bool frame() override {
    image_.clear(vraster::Color{1, 1, 1, 1});
    const vraster::svg::RenderSettings settings;  // what svg::render uses by default
    for (const vraster::svg::DrawItem& item : doc_->items) {
      if (!item.is_fill()) continue;  // the fill benchmark compares fills only
      const vraster::FillOptions options{settings.rule_override.value_or(item.rule), settings.aa,
                                         settings.tolerance};
      renderer_.fill(image_, item.path, item.transform, item.color, options);
    }
    return true;
  }

  vraster::Image image() const override { return image_; }

 private:
  const vraster::svg::Document* doc_ = nullptr;
  vraster::Image image_;
  vraster::Renderer renderer_;
};

}  // namespace

std::unique_ptr<Engine> make_vraster_engine() { return std::make_unique<VrasterEngine>(); }

}  // namespace bench
