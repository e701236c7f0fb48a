#include "assets/catalog_labels.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "scene/nyu40.h"

namespace inet {
namespace {

/// One rule: `words` (alternatives separated by '|') are whole-word sequences looked for in
/// the piece's lower-cased name; `sh3d` restricts the rule to one Sweet Home 3D category.
/// The first matching rule decides. Specific names come before the general words they contain
/// ("coffee table" before "table", "toilet brush" before "toilet").
struct Rule {
  const char* words;
  const char* sh3d;      ///< "" = any category
  const char* category;  ///< ours, "" = none
  const char* nyu40;
  bool slot = false;  ///< CatalogLabel::slot
};

// clang-format off
constexpr Rule kRules[] = {
    // doors and windows
    {"window shutter", "", "", "blinds"},
    {"window blind", "", "blinds", "blinds"},
    {"elevator door|garage door|screen door|shower door", "", "", "door"},
    {"elevator", "", "", "otherstructure"},
    {"door", "Doors and windows", "door", "door"},
    {"window", "Doors and windows", "window", "window"},
    // beds
    {"opened convertible sofa", "", "bed_double", "bed"},
    {"bunk bed|mezzanine bed", "", "bunk_bed", "bed"},
    {"air mattress|sleeping bag|hammock", "", "", "bed"},
    {"child bed|baby bed|crib|captain s bed|day bed|hospital bed", "", "bed_single", "bed"},
    {"futon couch", "", "sofa", "sofa"},
    {"futon|bed", "", "bed_double", "bed"},
    {"bedside table|nightstand", "", "nightstand", "night_stand"},
    // seating
    {"sofa|couch|settee", "", "sofa", "sofa"},
    {"armchair", "Office", "office_chair", "chair"},
    {"armchair|puff|ryokan chair|winchester armchair", "", "armchair", "chair"},
    {"bar stool|stool", "", "stool", "chair"},
    {"chair", "Office", "office_chair", "chair"},
    {"wheelchair", "", "", "otherfurniture"},
    {"chair|class seat", "", "dining_chair", "chair"},
    {"piano bench|abdominal bench|bench|little bank|wood bank", "", "bench", "otherfurniture"},
    // tables (games first: "table tennis bat" is no table)
    {"table tennis bat", "", "", "otherprop"},
    {"pool table|table tennis|football table", "", "", "otherfurniture"},
    {"coffee table", "", "coffee_table", "table"},
    {"changing table|dressing table", "", "dresser", "dresser"},
    {"desk lamp", "", "table_lamp", "lamp"},
    {"desk table|wooden desk|desk", "", "desk", "desk"},
    {"tv stand|television cabinet", "", "tv_stand", "cabinet"},
    {"workbench|technical table", "", "desk", "desk"},
    {"table", "", "dining_table", "table"},
    // storage
    {"wardrobe|cupboard", "", "wardrobe", "cabinet"},
    {"chest freezer", "", "refrigerator", "refridgerator"},
    {"dresser|chest", "", "dresser", "dresser"},
    {"filing cabinet|safe|locked locker", "", "cabinet", "cabinet"},
    {"contemporary living room|full bookcase|bookcase|vertical shelves|shelves", "",
     "bookshelf", "bookshelf"},
    {"clothes rack|wall hanger", "", "coat_rack", "otherfurniture"},
    // kitchen ("island bath" is no kitchen island)
    {"island bath|corner bathtub", "", "bathtub", "bathtub"},
    {"fridge|refrigerator|large fridge", "", "refrigerator", "refridgerator"},
    {"washing machine|dryer machine", "", "washing_machine", "otherfurniture"},
    {"sink cabinet|sink", "Kitchen", "kitchen_sink_counter", "counter"},
    {"high cabinet", "", "cabinet", "cabinet"},
    {"upper cabinet|upper corner cabinet|upper shelves cabinet|glass door cabinet", "",
     "upper_cabinet", "cabinet"},
    {"island extension|island|lower cabinet|lower corner cabinet|drawers cabinet", "",
     "kitchen_counter", "counter"},
    {"cooktop|induction cooker|microwave|small oven|sandwich maker", "", "", "otherprop"},
    {"large stove|propane stove|double oven|oven|stove", "", "stove", "otherfurniture"},
    {"bowl with fruits|bowl with salad|bowl", "", "bowl", "otherprop"},
    {"coffee cup|coffee mug|plastic cup|cup|beer glass|cocktail glass", "", "mug", "otherprop"},
    {"bullet trash can|dustbin|recycling bin|trash", "", "trash_bin", "otherprop"},
    // bathroom
    {"toilet paper dispenser|toilet brush|towel rack", "", "", "otherprop"},
    {"toilets unit|toilet|bidet|urinal", "", "toilet", "toilet"},
    {"corner bathtub|island bath|bathtub|bath", "", "bathtub", "bathtub"},
    {"double vanity|vanity|washbasin|small lavatory|basin", "", "bathroom_basin", "sink"},
    {"shower curtain", "", "shower_curtain", "shower_curtain"},
    {"shower stall", "", "shower", "otherstructure"},
    {"towel", "", "towel", "towel"},
    {"radiator|furnace|fireplace|chimney|round chimney", "", "", "otherstructure"},
    // lights
    {"ceiling lamp|fluorescent light|track lights", "Lights", "ceiling_light", "lamp"},
    {"chandelier lamp|hanging light|pendant lamp", "Lights", "pendant_light", "lamp"},
    {"wall light|wall lamp artwork|wall spotlight|fluorescent strip", "Lights", "", "lamp"},
    {"candle|flashlight", "", "", "otherprop"},
    {"lamp|lantern", "Lights", "table_lamp", "lamp"},
    // living room and office things
    {"video projector|surveillance camera|cctv", "", "", "otherprop"},
    {"tv|television", "", "television", "television"},
    {"apple imac", "", "monitor", "television"},
    {"laptop|apple ibook|tablet", "", "laptop", "otherprop"},
    {"white board", "", "whiteboard", "whiteboard"},
    {"oriental rug|round carpet|bathmat|doormat|rug|carpet|tatami", "", "rug", "floor_mat"},
    {"curtain", "", "curtain", "curtain"},
    {"frame", "", "", "picture"},  // standing photo frames, not our wall pictures
    {"newspaper", "", "paper", "paper"},
    {"book", "", "books", "books"},
    {"flowers|tulips|white lily|orchids|vase", "", "vase", "otherprop"},
    {"christmas tree", "", "", "otherprop"},
    {"plant|ficus|bonsai tree|yucca|spathiphyllum|bamboo|cactus", "",
     "potted_plant", "otherprop"},
    {"cardboard box|open cardboard box|crate|box|trunck", "", "box", "box"},
    {"handbag|briefcase|backpack|suitcase|shopping basket|clothes basket", "", "bag", "bag"},
    {"sneakers|mocassin|woman shoes|slippers|bootie", "", "shoes", "otherprop"},
    {"folded clothes|hanging clothes|dress|skirt|trousers|short|jacket|suit|socket|hat|cap|"
     "glove",
     "Bedroom", "clothes", "clothes"},
    {"grand piano|upright piano|flipper|treadmill|indoor bike|fitness tower|aquarium", "", "",
     "otherfurniture"},
    // long or large props that are no furniture
    {"broom|electric guitar|umbrella|mower|step ladder|shower head and faucet|pallet", "", "",
     "otherprop"},
    {"iron railing|fence|shipping container", "", "", "otherstructure"},
    // small things that take the place of our props on supports (CatalogLabel::slot)
    {"oval plate|plate glass and cutlery|plate glasses and cutlery|plate|sushi tray|tray|apples|"
     "bread box|bread|butter|birthday cake|cup cake|hamburger|hot dog|steak|roasted chicken|"
     "french fries|chopping board|large pan",
     "", "bowl", "otherprop", true},
    {"teapot|creamer|salt shaker|sugar|old jar|spice tower|milk|yogurt bottle|wine bottle|"
     "beer bottle|baby bottle|coffee press|espresso kettle|boiler|toaster|coffee maker|mixer|"
     "blender|kitchen scale|utensils pot|knife stand|oil servers|pottery|medicine bottle|"
     "medicine box|bottle|flacon|cosmetics pot|soap|sponge|glass",
     "", "mug", "otherprop", true},
    {"candle|clock|deer|gift|wood toy|teddy bear|doll|car model|biplane|toy train|rubik s cube|"
     "chessboard|puzzle|card game|radio|speaker|mp3 base|mp3 station|mini stereo|headphones|"
     "reflex camera|camera|sunglasses|glasses|keys|wireless phone|phone|mobile phone|"
     "apple iphone|thermometer|calendar|penbox|stapler|tape measure|tape|scissors|ruler|"
     "text marker|letter tray|table fan|ashtray|hashtray|comb|brush|lip stick|watch|"
     "playstation|joystick|tv remote control|dvd player|keyboard|inkjet printer and scanner|"
     "xylophone|electronic scale|squeezer|sandwich maker|stone grill device|coffee machine",
     "", "vase", "otherprop", true},
    // people, and their animals (no NYU40 class of their own)
    {"horse|bulldog|dog|cat|siamese cat|chicken|rabbit", "Characters", "", "otherprop"},
    {"boy|girl|male|female|mannequin male|mannequin female", "Characters", "", "person"},
};
// clang-format on

/// The name lower-cased with every non-alphanumeric character turned into a space and one
/// space at each end, so whole words are found with " word ".
std::string normalise(std::string_view s) {
  std::string out = " ";
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    out += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : ' ';
  }
  out += ' ';
  // collapse runs of spaces
  std::string squeezed;
  for (char c : out)
    if (!(c == ' ' && !squeezed.empty() && squeezed.back() == ' ')) squeezed += c;
  return squeezed;
}

bool matchesWords(const std::string& name, std::string_view alternatives, std::string* hit) {
  size_t begin = 0;
  while (begin <= alternatives.size()) {
    size_t end = alternatives.find('|', begin);
    if (end == std::string_view::npos) end = alternatives.size();
    const std::string needle = normalise(alternatives.substr(begin, end - begin));
    if (needle.size() > 2 && name.find(needle) != std::string::npos) {
      *hit = needle.substr(1, needle.size() - 2);
      return true;
    }
    begin = end + 1;
  }
  return false;
}

/// Size rules on top of the name: a bed under 1.2 m wide is single, a "table" under 0.7 m
/// wide a side table and one under 0.6 m tall a coffee table, a table lamp over 0.9 m tall a
/// floor lamp (and one whose bulbs all sit in its lower 40 % a pendant light: a chandelier
/// named "Lamp"), a potted plant over 0.6 m tall a floor plant, a stove under 0.5 m tall (a
/// camping or countertop one) a prop.
void applySizeRules(const CatalogPiece& p, CatalogLabel& l) {
  const double w = p.width_cm, h = p.height_cm;
  if (l.category == "bed_double" && w < 120) l.category = "bed_single";
  if (l.category == "dining_table" && w < 70) l.category = "side_table";
  if (l.category == "dining_table" && h < 60) l.category = "coffee_table";
  if (l.category == "table_lamp" && h > 90) l.category = "floor_lamp";
  // a "lamp" whose bulbs all sit in its lower 40 % hangs from its top (a chandelier)
  if ((l.category == "table_lamp" || l.category == "floor_lamp") && !p.lights.empty() &&
      std::all_of(p.lights.begin(), p.lights.end(),
                  [&](const CatalogLightSource& b) { return b.position_cm.z() < 0.4 * h; }))
    l.category = "pendant_light";
  if (l.category == "potted_plant" && h > 60) l.category = "plant";
  if (l.category == "stove" && h < 50) {
    l.category.clear();
    l.nyu40 = 40;
  }
}

}  // namespace

CatalogLabel labelCatalogPiece(const CatalogPiece& piece) {
  const std::string name = normalise(piece.name);
  CatalogLabel label;
  for (const Rule& r : kRules) {
    if (*r.sh3d && piece.category != r.sh3d) continue;
    std::string hit;
    if (!matchesWords(name, r.words, &hit)) continue;
    label.nyu40 = nyu40FromName(r.nyu40).value_or(40);
    label.category = r.category;
    label.slot = r.slot;
    label.rule = "name '" + hit + "'";
    applySizeRules(piece, label);
    break;
  }
  if (label.rule.empty()) {
    const double largest = std::max({piece.width_cm, piece.depth_cm, piece.height_cm});
    if (piece.category == "Staircases") {
      label.nyu40 = 38;
      label.rule = "category 'Staircases'";
    } else if (piece.category == "Lights") {
      label.nyu40 = 35;
      label.rule = "category 'Lights'";
    } else {
      label.nyu40 = largest > 100 ? 39 : 40;
      label.rule = largest > 100 ? "default: larger than 1 m" : "default";
    }
  }
  const bool own_name = label.category.empty() || label.slot;
  label.kind = own_name ? normalise(piece.name) : label.category;
  if (own_name) {  // "Wall flat TV" -> "wall_flat_tv"
    std::string k;
    for (char c : label.kind.substr(1, label.kind.size() - 2)) k += c == ' ' ? '_' : c;
    label.kind = k;
  }
  return label;
}

}  // namespace inet
