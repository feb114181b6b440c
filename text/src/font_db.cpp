// The font database: faces from files, directories, fontconfig and the embedded font; CSS-style matching.
#include "vraster_text/font_db.hpp"

#include <fontconfig/fontconfig.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "font_impl.hpp"
#include FT_TRUETYPE_TABLES_H
#include "vraster/error.hpp"

namespace vraster::text {
namespace {

constexpr std::size_t kMaxFaces = 100'000;  // faces from all sources together
constexpr int kMaxFacesPerFile = 256;
constexpr std::size_t kMaxFallbackLookups = 20'000;  // distinct code points searched for in other fonts

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

bool is_font_file(const std::filesystem::path& p) {
  const std::string ext = lower(p.extension().string());
  return ext == ".ttf" || ext == ".otf" || ext == ".ttc" || ext == ".otc";
}

/// OS/2 usWidthClass 1..9 -> percent (CSS font-stretch keywords).
double width_class_percent(int width_class) {
  static constexpr double kPercent[] = {50, 62.5, 75, 87.5, 100, 112.5, 125, 150, 200};
  return width_class >= 1 && width_class <= 9 ? kPercent[width_class - 1] : 100;
}

/// The description of an open FreeType face.
FaceInfo describe(FT_Face face, const std::string& path, int index) {
  FaceInfo info;
  info.path = path;
  info.index = index;
  info.family = face->family_name ? face->family_name : "";
  info.slant = (face->style_flags & FT_STYLE_FLAG_ITALIC) ? FontSlant::Italic : FontSlant::Normal;
  info.weight = (face->style_flags & FT_STYLE_FLAG_BOLD) ? 700 : 400;
  info.variable = FT_HAS_MULTIPLE_MASTERS(face);
  if (const auto* os2 = static_cast<const TT_OS2*>(FT_Get_Sfnt_Table(face, FT_SFNT_OS2))) {
    if (os2->version != 0xFFFF) {
      if (os2->usWeightClass >= 1 && os2->usWeightClass <= 1000) info.weight = os2->usWeightClass;
      info.stretch = width_class_percent(os2->usWidthClass);
      if (os2->fsSelection & (1u << 9)) info.slant = FontSlant::Oblique;  // OBLIQUE bit
      if (os2->fsSelection & 1u) info.slant = FontSlant::Italic;
    }
  }
  return info;
}

/// Distance of a face's slant from the wanted one (CSS: italic prefers oblique next, oblique prefers italic).
int slant_rank(FontSlant want, FontSlant have) {
  if (want == have) return 0;
  if (want == FontSlant::Normal) return have == FontSlant::Oblique ? 1 : 2;
  return have == FontSlant::Normal ? 2 : 1;
}

/// CSS weight preference: a smaller number is a better match for `want`.
double weight_rank(int want, int have) {
  if (have == want) return 0;
  const double d = std::abs(have - want);
  if (want >= 400 && want <= 500) {
    if (have > want && have <= 500) return d;          // up to 500 first
    if (have < want) return 1000 + d;                  // then lighter
    return 2000 + d;                                   // then heavier
  }
  if (want < 400) return have < want ? d : 1000 + d;   // lighter first, then heavier
  return have > want ? d : 1000 + d;                   // heavier first, then lighter
}

/// CSS stretch preference.
double stretch_rank(double want, double have) {
  const double d = std::abs(have - want);
  if (d == 0) return 0;
  if (want <= 100) return have < want ? d : 1000 + d;  // narrower first
  return have > want ? d : 1000 + d;                   // wider first
}

}  // namespace

bool parse_generic_family(std::string_view name, GenericFamily& out) {
  const std::string n = lower(name);
  if (n == "serif") out = GenericFamily::Serif;
  else if (n == "sans-serif") out = GenericFamily::SansSerif;
  else if (n == "monospace") out = GenericFamily::Monospace;
  else if (n == "cursive") out = GenericFamily::Cursive;
  else if (n == "fantasy") out = GenericFamily::Fantasy;
  else return false;
  return true;
}

/// fontconfig's configuration, kept for per-character lookups among the system faces.
struct FontDb::SystemIndex {
  FcConfig* config = nullptr;
  std::map<std::pair<std::string, int>, int> by_file;  // (path, index) -> face
  ~SystemIndex() {
    if (config) FcConfigDestroy(config);
  }
};

FontDb::FontDb() = default;
FontDb::~FontDb() = default;

std::size_t FontDb::add_file(const std::string& path) {
  FT_Library library = nullptr;
  if (FT_Init_FreeType(&library) != 0) throw Error("FreeType failed to initialise");
  std::size_t added = 0;
  int count = 1;
  try {
    for (int i = 0; i < count && i < kMaxFacesPerFile; ++i) {
      FT_Face face = nullptr;
      if (FT_New_Face(library, path.c_str(), i, &face) != 0) {
        if (i == 0) throw Error("font " + quoted(path, 1024) + ": not a font file FreeType can open");
        break;
      }
      count = static_cast<int>(face->num_faces);
      // Outline fonts, and colour bitmap fonts (CBDT, sbix: fixed sizes, drawn as images scaled to the size).
      const bool usable = (face->face_flags & FT_FACE_FLAG_SCALABLE) || (FT_HAS_COLOR(face) && face->num_fixed_sizes > 0);
      if (faces_.size() < kMaxFaces && usable) {
        faces_.push_back(describe(face, path, i));
        ++added;
      }
      FT_Done_Face(face);
    }
  } catch (...) {
    FT_Done_FreeType(library);
    throw;
  }
  FT_Done_FreeType(library);
  faces_changed();
  return added;
}

std::size_t FontDb::add_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error("font directory " + quoted(dir, 1024) + " is not a readable directory");
  std::vector<std::string> files;
  for (fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec) && is_font_file(it->path())) files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());  // a stable order: matches do not depend on the directory's order
  std::size_t added = 0;
  for (const std::string& f : files) {
    try {
      added += add_file(f);
    } catch (const Error& e) {
      warnings_.push_back(e.what());
    }
  }
  return added;
}

void FontDb::add_embedded_default() {
  const std::shared_ptr<Font> font = Font::load_default();
  FaceInfo info;
  info.family = font->family_name();
  faces_.push_back(info);
  faces_changed();
  loaded_.back() = font;
}

void FontDb::faces_changed() {
  loaded_.resize(faces_.size());
  broken_.resize(faces_.size());
  fallback_cache_.clear();
  match_cache_.clear();
  family_cache_.clear();
}

std::size_t FontDb::add_system_fonts() {
  if (!system_) system_ = std::make_unique<SystemIndex>();
  if (!system_->config) system_->config = FcInitLoadConfigAndFonts();
  if (!system_->config) return 0;
  FcPattern* pattern = FcPatternCreate();
  FcObjectSet* objects = FcObjectSetBuild(FC_FAMILY, FC_FILE, FC_INDEX, FC_WEIGHT, FC_SLANT, FC_WIDTH,
                                          FC_OUTLINE, FC_COLOR, FC_VARIABLE, nullptr);
  FcFontSet* set = FcFontList(system_->config, pattern, objects);
  std::size_t added = 0;
  for (int i = 0; set && i < set->nfont && faces_.size() < kMaxFaces; ++i) {
    FcPattern* p = set->fonts[i];
    FcChar8* file = nullptr;
    FcChar8* family = nullptr;
    FcBool outline = FcTrue;
    if (FcPatternGetString(p, FC_FILE, 0, &file) != FcResultMatch || !file) continue;
    if (FcPatternGetString(p, FC_FAMILY, 0, &family) != FcResultMatch || !family) continue;
    FcBool color = FcFalse;
    FcPatternGetBool(p, FC_OUTLINE, 0, &outline);
    FcPatternGetBool(p, FC_COLOR, 0, &color);
    if (!outline && !color) continue;  // colour bitmap fonts (CBDT, sbix) are drawn as images
    FaceInfo info;
    info.system = true;
    info.path = reinterpret_cast<const char*>(file);
    info.family = reinterpret_cast<const char*>(family);
    int index = 0, slant = FC_SLANT_ROMAN, width = FC_WIDTH_NORMAL;
    double weight = FC_WEIGHT_REGULAR;
    FcPatternGetInteger(p, FC_INDEX, 0, &index);
    FcPatternGetDouble(p, FC_WEIGHT, 0, &weight);
    FcPatternGetInteger(p, FC_SLANT, 0, &slant);
    FcPatternGetInteger(p, FC_WIDTH, 0, &width);
    info.index = index & 0xFFFF;  // the upper bits name a named instance of a variable font
    info.weight = std::clamp(static_cast<int>(std::lround(FcWeightToOpenTypeDouble(weight))), 1, 1000);
    info.slant = slant == FC_SLANT_ITALIC ? FontSlant::Italic : slant == FC_SLANT_OBLIQUE ? FontSlant::Oblique
                                                                                        : FontSlant::Normal;
    info.stretch = std::clamp(static_cast<double>(width), 50.0, 200.0);
    FcBool variable = FcFalse;
    FcPatternGetBool(p, FC_VARIABLE, 0, &variable);
    info.variable = variable;
    if (system_->by_file.count({info.path, index})) continue;
    system_->by_file[{info.path, index}] = static_cast<int>(faces_.size());
    faces_.push_back(std::move(info));
    ++added;
  }
  if (set) FcFontSetDestroy(set);
  FcObjectSetDestroy(objects);
  FcPatternDestroy(pattern);
  // Generic families not set yet: the family fontconfig's configuration picks for them.
  static constexpr const char* kGenerics[] = {"serif", "sans-serif", "monospace", "cursive", "fantasy"};
  for (std::size_t g = 0; g < generic_.size(); ++g) {
    if (!generic_[g].empty()) continue;
    FcPattern* want = FcNameParse(reinterpret_cast<const FcChar8*>(kGenerics[g]));
    if (!want) continue;
    FcConfigSubstitute(system_->config, want, FcMatchPattern);
    FcDefaultSubstitute(want);
    FcResult result = FcResultNoMatch;
    if (FcPattern* match = FcFontMatch(system_->config, want, &result)) {
      FcChar8* family = nullptr;
      if (FcPatternGetString(match, FC_FAMILY, 0, &family) == FcResultMatch && family)
        generic_[g] = reinterpret_cast<const char*>(family);
      FcPatternDestroy(match);
    }
    FcPatternDestroy(want);
  }
  faces_changed();
  return added;
}

void FontDb::set_generic_family(GenericFamily generic, std::string family) {
  generic_[static_cast<std::size_t>(generic)] = std::move(family);
  match_cache_.clear();
  family_cache_.clear();
}

void FontDb::set_default_family(std::string family) {
  default_family_ = std::move(family);
  match_cache_.clear();
  family_cache_.clear();
}

std::vector<int> FontDb::family_candidates(std::string_view family) const {  // a copy: loading may clear the cache
  const std::string key(family);
  if (const auto it = family_cache_.find(key); it != family_cache_.end()) return it->second;
  if (family_cache_.size() >= 4096) family_cache_.clear();
  return family_cache_[key] = family_candidates_uncached(family);
}

std::vector<int> FontDb::family_candidates_uncached(std::string_view family) const {
  std::string name(family);
  GenericFamily generic;
  if (parse_generic_family(family, generic)) {
    name = generic_[static_cast<std::size_t>(generic)];
    if (name.empty()) return {};
  }
  const std::string want = lower(name);
  std::vector<int> out;
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    if (!broken_[i] && lower(faces_[i].family) == want) out.push_back(static_cast<int>(i));
  }
  return out;
}

int FontDb::best_of(const std::vector<int>& candidates, const FontQuery& q) const {
  int best = -1;
  double best_key[3] = {0, 0, 0};
  for (const int i : candidates) {
    const FaceInfo& f = faces_[static_cast<std::size_t>(i)];
    const double key[3] = {stretch_rank(q.stretch, f.stretch), static_cast<double>(slant_rank(q.slant, f.slant)),
                           weight_rank(q.weight, f.weight)};
    if (best < 0 || std::lexicographical_compare(key, key + 3, best_key, best_key + 3)) {
      best = i;
      std::copy(key, key + 3, best_key);
    }
  }
  return best;
}

std::shared_ptr<Font> FontDb::load(int index) {
  const auto i = static_cast<std::size_t>(index);
  if (loaded_[i]) return loaded_[i];
  if (broken_[i]) return nullptr;
  try {
    loaded_[i] = Font::load_file(faces_[i].path, faces_[i].index);
  } catch (const Error& e) {
    broken_[i] = true;
    match_cache_.clear();  // matches may have picked this face
    family_cache_.clear();
    warnings_.push_back(e.what());
    return nullptr;
  }
  return loaded_[i];
}

int FontDb::match_index(const FontQuery& query) {
  std::string key;
  for (const std::string& f : query.families) {
    key += f;
    key += '\n';
  }
  key += std::to_string(query.weight);
  key += ' ';
  key += std::to_string(static_cast<int>(query.slant));
  key += ' ';
  key += std::to_string(query.stretch);
  if (const auto it = match_cache_.find(key); it != match_cache_.end()) return it->second;
  if (match_cache_.size() >= 4096) match_cache_.clear();
  return match_cache_[key] = match_uncached(query);
}

int FontDb::match_uncached(const FontQuery& query) {
  // A face that fails to load is marked broken and the match is tried again without it.
  for (int attempt = 0; attempt < 64; ++attempt) {
    int found = -1;
    for (const std::string& family : query.families) {
      found = best_of(family_candidates(family), query);
      if (found >= 0) break;
    }
    if (found < 0) found = best_of(family_candidates(default_family_), query);
    if (found < 0) {
      std::vector<int> all;
      for (std::size_t i = 0; i < faces_.size(); ++i) {
        if (!broken_[i]) all.push_back(static_cast<int>(i));
      }
      found = best_of(all, query);
    }
    if (found < 0 || load(found)) return found;
  }
  return -1;
}

std::shared_ptr<Font> FontDb::match(const FontQuery& query) {
  const int i = match_index(query);
  if (i < 0) return nullptr;
  if (faces_[static_cast<std::size_t>(i)].variable) {
    if (std::shared_ptr<Font> f = instance(i, query)) return f;
  }
  return load(i);
}

/// A variable face at the axes the query implies: wght from the weight, wdth from the stretch, slnt / ital from
/// the slant (CSS Fonts 4, "font-optical-sizing" aside), then font-variation-settings over them. One Font per
/// distinct setting (each has its own outline cache).
std::shared_ptr<Font> FontDb::instance(int index, const FontQuery& query) {
  std::vector<FontVariation> axes = {
      {FontVariation::make_tag("wght"), static_cast<double>(query.weight)},
      {FontVariation::make_tag("wdth"), query.stretch},
      {FontVariation::make_tag("slnt"), query.slant == FontSlant::Oblique ? -14.0 : 0.0},
      {FontVariation::make_tag("ital"), query.slant == FontSlant::Italic ? 1.0 : 0.0}};
  if (query.optical_size > 0) axes.push_back({FontVariation::make_tag("opsz"), query.optical_size});
  for (const FontVariation& v : query.variations) {
    const auto same = std::find_if(axes.begin(), axes.end(), [&](const FontVariation& a) { return a.tag == v.tag; });
    if (same != axes.end()) same->value = v.value;
    else axes.push_back(v);
  }
  std::string key;
  for (const FontVariation& v : axes) key += std::to_string(v.tag) + "=" + std::to_string(v.value) + ",";
  const auto found = instances_.find({index, key});
  if (found != instances_.end()) return found->second;
  if (instances_.size() >= 256) instances_.clear();  // bounded: a document cannot pile up font copies
  const FaceInfo& face = faces_[static_cast<std::size_t>(index)];
  std::shared_ptr<Font> font;
  try {
    font = face.path.empty() ? Font::load_default() : Font::load_file(face.path, face.index);
  } catch (const Error& e) {
    warnings_.push_back(e.what());
    return nullptr;
  }
  font->set_variations(axes);
  instances_[{index, key}] = font;
  return font;
}

bool FontDb::face_has(int index, char32_t c) {
  const std::shared_ptr<Font> font = load(index);
  return font && font->has_glyph(c);
}

FontList FontDb::fonts_for(const FontQuery& query, std::u32string_view text) {
  FontList list;
  const std::shared_ptr<Font> primary = match(query);
  if (!primary) return list;
  list.add(primary);
  auto covered = [&](char32_t c) {
    return std::any_of(list.fonts.begin(), list.fonts.end(), [&](const auto& f) { return f->has_glyph(c); });
  };
  for (const char32_t c : text) {
    if (c < 0x20 || c == 0x2028 || c == 0x2029 || covered(c)) continue;
    // First the query's own families (another style of them may have it), best style match first.
    std::vector<int> own;
    for (const std::string& family : query.families) {
      for (const int i : family_candidates(family)) {
        if (face_has(i, c)) own.push_back(i);
      }
    }
    int found = best_of(own, query);
    if (found >= 0) {
    } else if (const auto cached = fallback_cache_.find(c); cached != fallback_cache_.end()) {
      found = cached->second;
    } else if (fallback_cache_.size() >= kMaxFallbackLookups) {
      continue;  // bounded work: a text of a million distinct characters does not query a million times
    } else {
      // Then the files and directories given (best style match among those that have it), then the system's.
      std::vector<int> given;
      for (std::size_t i = 0; i < faces_.size(); ++i) {
        if (!faces_[i].system && !broken_[i] && face_has(static_cast<int>(i), c)) given.push_back(static_cast<int>(i));
      }
      found = best_of(given, query);
      if (found < 0 && system_ && system_->config) {
        FcPattern* pattern = FcPatternCreate();
        FcCharSet* set = FcCharSetCreate();
        FcCharSetAddChar(set, static_cast<FcChar32>(c));
        FcPatternAddCharSet(pattern, FC_CHARSET, set);
        FcObjectSet* objects = FcObjectSetBuild(FC_FILE, FC_INDEX, nullptr);
        FcFontSet* fonts = FcFontList(system_->config, pattern, objects);
        std::vector<int> candidates;
        for (int k = 0; fonts && k < fonts->nfont; ++k) {
          FcChar8* file = nullptr;
          int index = 0;
          if (FcPatternGetString(fonts->fonts[k], FC_FILE, 0, &file) != FcResultMatch || !file) continue;
          FcPatternGetInteger(fonts->fonts[k], FC_INDEX, 0, &index);
          const auto it = system_->by_file.find({reinterpret_cast<const char*>(file), index});
          if (it != system_->by_file.end() && !broken_[static_cast<std::size_t>(it->second)])
            candidates.push_back(it->second);
        }
        std::sort(candidates.begin(), candidates.end());  // fontconfig's list order is not stable
        if (fonts) FcFontSetDestroy(fonts);
        FcObjectSetDestroy(objects);
        FcCharSetDestroy(set);
        FcPatternDestroy(pattern);
        // Best style match among the faces that have it, loading only that one.
        while (!candidates.empty()) {
          const int best = best_of(candidates, query);
          if (face_has(best, c)) {
            found = best;
            break;
          }
          candidates.erase(std::find(candidates.begin(), candidates.end(), best));
        }
      }
      fallback_cache_[c] = found;
    }
    if (found >= 0) {
      if (const std::shared_ptr<Font> f = load(found);
          f && std::find(list.fonts.begin(), list.fonts.end(), f) == list.fonts.end() && list.fonts.size() < 64)
        list.add(f);
    }
  }
  return list;
}

}  // namespace vraster::text
