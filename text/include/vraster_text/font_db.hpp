// vraster_text: a font database. Fonts come only from the sources the caller names: font files and directories,
// the fonts fontconfig knows (the system's), and the embedded default font. Queries follow CSS font matching,
// simplified: the first family of a list that the database has, then stretch, style and weight (CSS Fonts 4,
// 5.2). Characters the chosen font lacks fall back to any font of the database that has them.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vraster_text/font.hpp"

namespace vraster::text {

enum class FontSlant : std::uint8_t { Normal, Italic, Oblique };

/// What a run of text asks for.
struct FontQuery {
  std::vector<std::string> families;  ///< in order of preference; generic names (serif, sans-serif, ...) allowed
  int weight = 400;                   ///< 1..1000 (normal 400, bold 700)
  FontSlant slant = FontSlant::Normal;
  double stretch = 100;               ///< percent of normal width, 50..200
  /// Axis values for a variable font (font-variation-settings); they override the ones weight, stretch and slant
  /// set on such a font (wght, wdth, slnt, ital).
  std::vector<FontVariation> variations;
  double optical_size = 0;  ///< px: sets the opsz axis of a variable font (CSS font-optical-sizing: auto); 0: not
};

/// One face the database knows (not loaded until a query picks it).
struct FaceInfo {
  std::string path;     ///< empty: the embedded default font
  int index = 0;        ///< face index in a collection
  std::string family;
  int weight = 400;
  FontSlant slant = FontSlant::Normal;
  double stretch = 100;
  bool system = false;  ///< found through fontconfig
  bool variable = false;  ///< has variation axes
};

/// The generic families CSS names.
enum class GenericFamily : std::uint8_t { Serif, SansSerif, Monospace, Cursive, Fantasy };
/// "serif" -> Serif and so on (ASCII case-insensitive); false for any other name.
bool parse_generic_family(std::string_view name, GenericFamily& out);

/// Faces from the sources given; loads a face on first use and keeps it. Not thread-safe (one per thread, or
/// guard it). Broken font files are skipped with a message in warnings(), never a crash.
class FontDb {
 public:
  FontDb();
  ~FontDb();
  FontDb(const FontDb&) = delete;
  FontDb& operator=(const FontDb&) = delete;

  /// Adds every font file (.ttf, .otf, .ttc, .otc, any case) in `dir` and its subdirectories. Returns the faces
  /// added. Throws vraster::Error when `dir` is not a readable directory.
  std::size_t add_directory(const std::string& dir);
  /// Adds every face of one font file. Throws vraster::Error when it is not a font.
  std::size_t add_file(const std::string& path);
  /// Adds the embedded default font (Noto Sans Regular).
  void add_embedded_default();
  /// Adds the faces fontconfig lists (the system's fonts). Returns the faces added (0 when fontconfig has none).
  std::size_t add_system_fonts();

  /// The family a generic name stands for (default: none; then any face is used for it).
  void set_generic_family(GenericFamily generic, std::string family);
  /// The family used when no family of a query's list is in the database (a name or a generic; default: serif).
  void set_default_family(std::string family);

  const std::vector<FaceInfo>& faces() const { return faces_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// The face CSS font matching picks for `query` (the default family when no family of the list matches; any
  /// face when that fails too); nullptr only when the database is empty or no face loads.
  std::shared_ptr<Font> match(const FontQuery& query);
  /// The index in faces() match() would load, or -1.
  int match_index(const FontQuery& query);
  /// match(query) first, then, for each code point of `text` the fonts so far lack, a face that has it (the
  /// query's family list first, then every face in the database, best style match first). Empty when the
  /// database has no usable face.
  FontList fonts_for(const FontQuery& query, std::u32string_view text);

 private:
  /// After faces were added: per-face slots for the new ones, and every cached answer forgotten.
  void faces_changed();
  int match_uncached(const FontQuery& query);
  int best_of(const std::vector<int>& candidates, const FontQuery& query) const;
  std::vector<int> family_candidates(std::string_view family) const;
  std::vector<int> family_candidates_uncached(std::string_view family) const;
  std::shared_ptr<Font> load(int index);
  bool face_has(int index, char32_t c);

  std::vector<FaceInfo> faces_;
  std::vector<std::shared_ptr<Font>> loaded_;  // per face; null until loaded
  std::vector<bool> broken_;                   // per face: failed to load
  std::array<std::string, 5> generic_;
  std::string default_family_ = "serif";
  std::map<char32_t, int> fallback_cache_;     // code point -> face index (-1: none)
  std::map<std::string, int> match_cache_;     // query -> match_index
  mutable std::map<std::string, std::vector<int>> family_cache_;  // family name -> faces (family_candidates)
  std::map<std::pair<int, std::string>, std::shared_ptr<Font>> instances_;  // variable faces at given axes
  std::shared_ptr<Font> instance(int index, const FontQuery& query);
  std::vector<std::string> warnings_;
  struct SystemIndex;
  std::unique_ptr<SystemIndex> system_;        // fontconfig's charset lookups for system faces
};

}  // namespace vraster::text
