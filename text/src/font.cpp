// Fonts: FreeType faces (outlines) and HarfBuzz fonts (shaping) over the same bytes.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "font_impl.hpp"
#include <hb-ot.h>
#include FT_MULTIPLE_MASTERS_H
#include FT_OUTLINE_H
#include FT_TRUETYPE_TABLES_H
#include FT_TRUETYPE_TAGS_H
#include "vraster/error.hpp"
#include "vraster/files.hpp"

namespace vraster::text {
namespace {

std::atomic<std::uint64_t> next_font_id{1};

// FreeType's own table of error messages (FT_Error_String returns null unless FreeType was built with error
// strings, which Debian's is not): fterrors.h expands FT_ERRORDEF once per error when re-included like this.
#undef FTERRORS_H_
#define FT_ERRORDEF(e, v, s) {v, s},
#define FT_ERROR_START_LIST {
#define FT_ERROR_END_LIST {0, nullptr}};
struct FreeTypeErrorText {
  int code;
  const char* text;
};
const FreeTypeErrorText kFreeTypeErrors[] =
#include FT_ERRORS_H

std::string ft_error_text(FT_Error e) {
  switch (e) {
    case FT_Err_Unknown_File_Format: return "not a font file FreeType knows (unknown file format)";
    case FT_Err_Invalid_File_Format: return "invalid or corrupt font data";
    case FT_Err_Invalid_Argument: return "no face with that index";
    case FT_Err_Invalid_Table: return "a font table is broken";
    case FT_Err_Out_Of_Memory: return "out of memory";
    default: break;
  }
  if (const char* s = FT_Error_String(e)) return s;
  for (const FreeTypeErrorText& t : kFreeTypeErrors) {
    if (t.text && t.code == e) return t.text;
  }
  return "FreeType error " + std::to_string(e);
}

std::uint32_t read_u16(const std::uint8_t* p) { return std::uint32_t{p[0]} << 8 | p[1]; }
std::uint32_t read_u32(const std::uint8_t* p) { return read_u16(p) << 16 | read_u16(p + 2); }

/// A TrueType font's loca table must hold num_glyphs + 1 non-decreasing offsets, none past the end of glyf.
/// FreeType tolerates a broken one by giving the glyphs it cannot place no outline, which would draw blank text
/// with no error; checking it once at load turns that into a message.
void check_glyph_locations(FT_Face face, const std::string& name) {
  FT_ULong loca_length = 0, glyf_length = 0;
  if (FT_Load_Sfnt_Table(face, TTAG_loca, 0, nullptr, &loca_length) != 0) return;  // no loca: not glyf-based
  if (FT_Load_Sfnt_Table(face, TTAG_glyf, 0, nullptr, &glyf_length) != 0) {
    throw Error("font " + quoted(name, 1024) + ": has a loca table but no glyf table");
  }
  const auto* head = static_cast<const TT_Header*>(FT_Get_Sfnt_Table(face, FT_SFNT_HEAD));
  if (!head) return;
  const bool long_offsets = head->Index_To_Loc_Format != 0;
  const std::size_t count = static_cast<std::size_t>(face->num_glyphs) + 1;
  const std::size_t entry = long_offsets ? 4 : 2;
  if (loca_length < count * entry) {
    throw Error("font " + quoted(name, 1024) + ": the loca table is too short for " +
                std::to_string(face->num_glyphs) + " glyphs (corrupt font)");
  }
  std::vector<std::uint8_t> loca(loca_length);
  if (FT_Load_Sfnt_Table(face, TTAG_loca, 0, loca.data(), &loca_length) != 0) return;
  std::uint64_t previous = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t offset = long_offsets ? read_u32(&loca[i * 4]) : std::uint64_t{read_u16(&loca[i * 2])} * 2;
    if (offset < previous || offset > glyf_length) {
      throw Error("font " + quoted(name, 1024) + ": the loca table is corrupt (the offset of glyph " +
                  std::to_string(i) + " is " + (offset < previous ? "before the previous glyph's" : "past the glyf table") +
                  ")");
    }
    previous = offset;
  }
}

struct DecomposeState {
  Path* path;
  double sx, sy;
  bool open = false;
  Point at(const FT_Vector* v) const { return {static_cast<double>(v->x) * sx, -static_cast<double>(v->y) * sy}; }
};

int on_move(const FT_Vector* to, void* user) {
  auto* s = static_cast<DecomposeState*>(user);
  if (s->open) s->path->close();
  s->path->move_to(s->at(to));
  s->open = true;
  return 0;
}
int on_line(const FT_Vector* to, void* user) {
  auto* s = static_cast<DecomposeState*>(user);
  s->path->line_to(s->at(to));
  return 0;
}
int on_conic(const FT_Vector* control, const FT_Vector* to, void* user) {
  auto* s = static_cast<DecomposeState*>(user);
  s->path->quad_to(s->at(control), s->at(to));
  return 0;
}
int on_cubic(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
  auto* s = static_cast<DecomposeState*>(user);
  s->path->cubic_to(s->at(c1), s->at(c2), s->at(to));
  return 0;
}

/// The lower-left corner of the box of a glyph's outline points in font units (y up), as HarfBuzz reads the
/// glyf / CFF data (FreeType does not load outlines of a font with an sbix table); nothing without an outline.
std::optional<Point> outline_corner(hb_font_t* font, std::uint32_t glyph) {
  struct Corner {
    double x = INFINITY, y = INFINITY;
    void add(float px, float py) {
      x = std::min(x, double(px));
      y = std::min(y, double(py));
    }
  } corner;
  hb_draw_funcs_t* funcs = hb_draw_funcs_create();
  auto move = [](hb_draw_funcs_t*, void* c, hb_draw_state_t*, float x, float y, void*) { static_cast<Corner*>(c)->add(x, y); };
  auto quad = [](hb_draw_funcs_t*, void* c, hb_draw_state_t*, float cx, float cy, float x, float y, void*) {
    static_cast<Corner*>(c)->add(cx, cy);
    static_cast<Corner*>(c)->add(x, y);
  };
  auto cubic = [](hb_draw_funcs_t*, void* c, hb_draw_state_t*, float c1x, float c1y, float c2x, float c2y, float x,
                  float y, void*) {
    static_cast<Corner*>(c)->add(c1x, c1y);
    static_cast<Corner*>(c)->add(c2x, c2y);
    static_cast<Corner*>(c)->add(x, y);
  };
  hb_draw_funcs_set_move_to_func(funcs, move, nullptr, nullptr);
  hb_draw_funcs_set_line_to_func(funcs, move, nullptr, nullptr);
  hb_draw_funcs_set_quadratic_to_func(funcs, quad, nullptr, nullptr);
  hb_draw_funcs_set_cubic_to_func(funcs, cubic, nullptr, nullptr);
  hb_font_get_glyph_shape(font, glyph, funcs, &corner);
  hb_draw_funcs_destroy(funcs);
  if (!std::isfinite(corner.x) || !std::isfinite(corner.y)) return std::nullopt;
  return Point{corner.x, corner.y};
}

}  // namespace

void check_font_size(double size) {
  if (!std::isfinite(size) || size <= 0) {
    throw Error("font size must be a positive number of pixels (got " + std::to_string(size) + ")");
  }
  if (size > kMaxFontSize) {
    throw Error("font size " + std::to_string(size) + " px is too large (at most " +
                std::to_string(static_cast<int>(kMaxFontSize)) + " px)");
  }
}

void decompose_outline(const FT_Outline& outline, double sx, double sy, Path& out) {
  FT_Outline_Funcs funcs{};
  funcs.move_to = on_move;
  funcs.line_to = on_line;
  funcs.conic_to = on_conic;
  funcs.cubic_to = on_cubic;
  DecomposeState state{&out, sx, sy};
  FT_Outline copy = outline;
  if (FT_Outline_Decompose(&copy, &funcs, &state) != 0) {
    out.clear();  // a broken outline draws nothing rather than something half-made
    return;
  }
  if (state.open) out.close();
}

Font::Impl::~Impl() {
  if (hb) hb_font_destroy(hb);
  if (face) FT_Done_Face(face);
  if (library) FT_Done_FreeType(library);
}

bool Font::Impl::load(std::uint32_t glyph, FT_Int32 flags) {
  if (glyph >= static_cast<std::uint32_t>(face->num_glyphs) || !FT_IS_SCALABLE(face)) return false;
  // A glyph the font lists but FreeType cannot load means corrupt glyph data: an error, not a blank glyph.
  if (const FT_Error e = FT_Load_Glyph(face, glyph, flags); e != 0) {
    throw Error("font " + quoted(name, 1024) + ": glyph " + std::to_string(glyph) + " cannot be loaded: " +
                ft_error_text(e));
  }
  return face->glyph->format == FT_GLYPH_FORMAT_OUTLINE;
}

Font::Font(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Font::~Font() = default;

std::shared_ptr<Font> Font::open(std::unique_ptr<Impl> impl, int face_index) {
  if (face_index < 0 || face_index > 0xFFFF) {
    throw Error("font '" + impl->name + "': face index " + std::to_string(face_index) + " is out of range");
  }
  if (FT_Init_FreeType(&impl->library) != 0) throw Error("font '" + impl->name + "': cannot start FreeType");
  const FT_Error e = FT_New_Memory_Face(impl->library, impl->bytes.data(), static_cast<FT_Long>(impl->bytes.size()),
                                        face_index, &impl->face);
  if (e != 0) {
    throw Error("font '" + impl->name + "' (face " + std::to_string(face_index) + "): " + ft_error_text(e));
  }
  if (impl->face->units_per_EM == 0 && FT_IS_SCALABLE(impl->face)) {
    throw Error("font '" + impl->name + "': units per em is 0 (corrupt head table)");
  }
  check_glyph_locations(impl->face, impl->name);
  hb_blob_t* blob = hb_blob_create(reinterpret_cast<const char*>(impl->bytes.data()),
                                   static_cast<unsigned>(impl->bytes.size()), HB_MEMORY_MODE_READONLY, nullptr, nullptr);
  hb_face_t* face = hb_face_create(blob, static_cast<unsigned>(face_index));
  hb_blob_destroy(blob);
  impl->hb = hb_font_create(face);
  hb_face_destroy(face);
  const int upem = impl->face->units_per_EM ? impl->face->units_per_EM : 1000;
  hb_font_set_scale(impl->hb, upem, upem);
  if (FT_HAS_COLOR(impl->face)) {
    for (int i = 0; i < impl->face->num_fixed_sizes; ++i) {
      const FT_Bitmap_Size& strike = impl->face->available_sizes[i];
      if (strike.y_ppem > 0 &&
          (impl->color_strike < 0 || strike.y_ppem > impl->face->available_sizes[impl->color_strike].y_ppem))
        impl->color_strike = i;
    }
  }
  impl->id = next_font_id.fetch_add(1);
  return std::shared_ptr<Font>(new Font(std::move(impl)));
}

std::shared_ptr<Font> Font::load_file(const std::string& path, int face_index) {
  auto impl = std::make_unique<Impl>();
  impl->owned = read_file_limited(path, kMaxFontFileBytes, "font");
  if (impl->owned.empty()) throw Error("font " + quoted(path, 1024) + ": the file is empty");
  impl->bytes = impl->owned;
  impl->name = path;
  return open(std::move(impl), face_index);
}

std::shared_ptr<Font> Font::load_memory(std::vector<std::uint8_t> bytes, int face_index, const std::string& name) {
  if (bytes.empty()) throw Error("font '" + name + "': no data");
  auto impl = std::make_unique<Impl>();
  impl->owned = std::move(bytes);
  impl->bytes = impl->owned;
  impl->name = name;
  return open(std::move(impl), face_index);
}

std::shared_ptr<Font> Font::load_default() {
  auto impl = std::make_unique<Impl>();
  impl->bytes = default_font_data();
  impl->name = "<default: Noto Sans Regular>";
  return open(std::move(impl), 0);
}

std::uint64_t Font::id() const { return impl_->id; }
const std::string& Font::name() const { return impl_->name; }
std::string Font::family_name() const { return impl_->face->family_name ? impl_->face->family_name : ""; }
std::string Font::style_name() const { return impl_->face->style_name ? impl_->face->style_name : ""; }
int Font::units_per_em() const { return impl_->face->units_per_EM ? impl_->face->units_per_EM : 1000; }
int Font::glyph_count() const { return static_cast<int>(impl_->face->num_glyphs); }
int Font::face_count() const { return static_cast<int>(impl_->face->num_faces); }
bool Font::has_outlines() const { return FT_IS_SCALABLE(impl_->face); }
bool Font::has_color_bitmaps() const { return impl_->color_strike >= 0; }

const ColorBitmap* Font::color_bitmap(std::uint32_t glyph) const {
  Impl& im = *impl_;
  if (im.color_strike < 0 || glyph >= static_cast<std::uint32_t>(im.face->num_glyphs)) return nullptr;
  auto it = im.color_bitmaps.find(glyph);
  if (it == im.color_bitmaps.end()) it = im.color_bitmaps.emplace(glyph, im.load_color_bitmap(glyph)).first;
  return it->second ? &*it->second : nullptr;
}

std::optional<ColorBitmap> Font::Impl::load_color_bitmap(std::uint32_t glyph) {
  constexpr unsigned kMaxSide = 4096;
  sized_at = -1;  // the face's size is the strike's from here on (hinted loads set theirs again)
  // A glyph without a bitmap in the strike (a space, say) or with undecodable image data simply has none: the
  // outline, if any, is drawn instead.
  if (FT_Select_Size(face, color_strike) != 0 || FT_Load_Glyph(face, glyph, FT_LOAD_COLOR) != 0) return std::nullopt;
  const FT_GlyphSlot slot = face->glyph;
  const FT_Bitmap& bitmap = slot->bitmap;
  if (slot->format != FT_GLYPH_FORMAT_BITMAP || bitmap.pixel_mode != FT_PIXEL_MODE_BGRA || bitmap.width == 0 ||
      bitmap.rows == 0 || bitmap.width > kMaxSide || bitmap.rows > kMaxSide || !bitmap.buffer)
    return std::nullopt;
  const unsigned row_bytes = static_cast<unsigned>(std::abs(bitmap.pitch));
  if (row_bytes < bitmap.width * 4) return std::nullopt;
  auto image = std::make_shared<Image>(static_cast<int>(bitmap.width), static_cast<int>(bitmap.rows));
  for (unsigned y = 0; y < bitmap.rows; ++y) {
    // A negative pitch stores the rows bottom-up.
    const std::uint8_t* row = bitmap.buffer + static_cast<std::size_t>(bitmap.pitch < 0 ? bitmap.rows - 1 - y : y) * row_bytes;
    for (unsigned x = 0; x < bitmap.width; ++x) {
      const std::uint8_t* bgra = row + x * 4;
      std::uint8_t* rgba = image->pixel(static_cast<int>(x), static_cast<int>(y));
      const std::uint8_t a = bgra[3];
      // Premultiplied already (FreeType's BGRA); a channel above alpha is corrupt data, clamped.
      rgba[0] = std::min(bgra[2], a);
      rgba[1] = std::min(bgra[1], a);
      rgba[2] = std::min(bgra[0], a);
      rgba[3] = a;
    }
  }
  ColorBitmap out;
  out.image = std::move(image);
  out.ppem = face->available_sizes[color_strike].y_ppem / 64.0;
  out.left = slot->bitmap_left;
  out.top = -slot->bitmap_top;
  // sbix: the table places the image at the glyph's origin, but Skia and CoreText (so the browsers) move it to
  // where the glyph's outline would be, by the outline's left and bottom; documents are made to look right there.
  FT_ULong sbix_length = 0;
  if (FT_Load_Sfnt_Table(face, FT_MAKE_TAG('s', 'b', 'i', 'x'), 0, nullptr, &sbix_length) == 0) {
    if (const std::optional<Point> corner = outline_corner(hb, glyph)) {
      const double k = out.ppem / (face->units_per_EM ? face->units_per_EM : 1000);
      out.left += corner->x * k;
      out.top -= corner->y * k;
    }
  }
  return out;
}

std::uint32_t Font::glyph_index(char32_t codepoint) const {
  auto it = impl_->cmap.find(codepoint);
  if (it != impl_->cmap.end()) return it->second;
  hb_codepoint_t g = 0;
  if (!hb_font_get_nominal_glyph(impl_->hb, codepoint, &g)) g = 0;
  impl_->cmap.emplace(codepoint, g);
  return g;
}

FontMetrics Font::metrics(double size) const {
  check_font_size(size);
  hb_font_extents_t ext{};
  hb_font_get_h_extents(impl_->hb, &ext);
  const double s = size / units_per_em();
  return {-ext.ascender * s, -ext.descender * s, ext.line_gap * s};
}

bool Font::is_variable() const { return FT_HAS_MULTIPLE_MASTERS(impl_->face); }

bool Font::set_variations(std::span<const FontVariation> values) {
  const FT_Face face = impl_->face;
  if (!FT_HAS_MULTIPLE_MASTERS(face)) return false;
  FT_MM_Var* mm = nullptr;
  if (FT_Get_MM_Var(face, &mm) != 0 || !mm) return false;
  std::vector<FT_Fixed> coords(mm->num_axis);
  std::vector<hb_variation_t> hb;
  for (FT_UInt i = 0; i < mm->num_axis; ++i) {
    const FT_Var_Axis& axis = mm->axis[i];
    const double lo = axis.minimum / 65536.0, hi = axis.maximum / 65536.0;
    double v = axis.def / 65536.0;
    for (const FontVariation& fv : values) {
      if (fv.tag == axis.tag && std::isfinite(fv.value)) v = fv.value;
    }
    v = std::clamp(v, std::min(lo, hi), std::max(lo, hi));
    coords[i] = static_cast<FT_Fixed>(std::lround(v * 65536.0));
    hb.push_back(hb_variation_t{static_cast<hb_tag_t>(axis.tag), static_cast<float>(v)});
  }
  FT_Done_MM_Var(impl_->library, mm);
  if (FT_Set_Var_Design_Coordinates(face, static_cast<FT_UInt>(coords.size()), coords.data()) != 0) return false;
  hb_font_set_variations(impl_->hb, hb.data(), static_cast<unsigned>(hb.size()));
  impl_->outlines.clear();
  impl_->sized_at = -1;
  impl_->id = next_font_id.fetch_add(1);
  return true;
}

bool Font::has_substitution_feature(std::string_view tag) const {
  if (tag.size() != 4) return false;
  const hb_tag_t t = hb_tag_from_string(tag.data(), 4);
  hb_face_t* face = hb_font_get_face(impl_->hb);
  hb_tag_t tags[64];
  for (unsigned start = 0;; start += 64) {
    unsigned count = 64;
    const unsigned total = hb_ot_layout_table_get_feature_tags(face, HB_OT_TAG_GSUB, start, &count, tags);
    for (unsigned i = 0; i < count; ++i) {
      if (tags[i] == t) return true;
    }
    if (count == 0 || start + count >= total) return false;
  }
}

DecorationMetrics Font::decoration_metrics(double size) const {
  check_font_size(size);
  const double s = size / units_per_em();
  const FT_Face face = impl_->face;
  DecorationMetrics m;
  m.underline_thickness = face->underline_thickness > 0 ? face->underline_thickness * s : size / 14;
  // The post table's underlinePosition, used as the line's centre (as browsers and resvg do). FreeType hands it
  // on lowered by half a thickness (FT_FaceRec: "the center of the underlining stem"), which is undone here.
  m.underline_position = face->underline_position != 0 || face->underline_thickness > 0
                             ? -(face->underline_position + face->underline_thickness / 2.0) * s
                             : size / 10;
  m.strikeout_thickness = m.underline_thickness;
  m.strikeout_position = -size * 0.3;
  m.subscript_offset = size * 0.2;
  m.superscript_offset = -size * 0.34;
  m.x_height = -size * 0.5;
  m.cap_height = -size * 0.7;
  const auto* os2 = static_cast<const TT_OS2*>(FT_Get_Sfnt_Table(face, FT_SFNT_OS2));
  if (os2 && os2->version != 0xFFFF) {
    if (os2->yStrikeoutSize > 0) m.strikeout_thickness = os2->yStrikeoutSize * s;
    if (os2->yStrikeoutPosition > 0) m.strikeout_position = -os2->yStrikeoutPosition * s;  // as the centre
    if (os2->ySubscriptYOffset != 0) m.subscript_offset = std::abs(os2->ySubscriptYOffset) * s;
    if (os2->ySuperscriptYOffset != 0) m.superscript_offset = -std::abs(os2->ySuperscriptYOffset) * s;
    if (os2->version >= 2 && os2->sxHeight > 0) m.x_height = -os2->sxHeight * s;
    if (os2->version >= 2 && os2->sCapHeight > 0) m.cap_height = -os2->sCapHeight * s;
  }
  return m;
}

double Font::advance(std::uint32_t glyph, double size) const {
  return hb_font_get_glyph_h_advance(impl_->hb, glyph) * (size / units_per_em());
}

const GlyphOutline& Font::glyph_outline(std::uint32_t glyph) const {
  auto it = impl_->outlines.find(glyph);
  if (it != impl_->outlines.end()) return it->second;
  GlyphOutline outline;
  if (impl_->load(glyph, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP)) {
    decompose_outline(impl_->face->glyph->outline, 1.0, 1.0, outline.path);
  }
  outline.control_box = outline.path.control_bounds();
  return impl_->outlines.emplace(glyph, std::move(outline)).first->second;
}

Path Font::outline(std::uint32_t glyph, double size, Hinting hinting) const {
  check_font_size(size);
  if (hinting == Hinting::None || !has_outlines()) {
    return outline_units(glyph).transformed(Affine::scale(size / units_per_em()));
  }
  Impl& im = *impl_;
  if (im.sized_at != size) {
    if (FT_Set_Char_Size(im.face, 0, static_cast<FT_F26Dot6>(std::lround(size * 64)), 72, 72) != 0) {
      throw Error("font '" + im.name + "': FreeType cannot set size " + std::to_string(size));
    }
    im.sized_at = size;
  }
  Path path;
  if (im.load(glyph, FT_LOAD_TARGET_LIGHT | FT_LOAD_NO_BITMAP)) {
    decompose_outline(im.face->glyph->outline, 1.0 / 64, 1.0 / 64, path);
  }
  return path;
}

}  // namespace vraster::text
