#pragma once
// What a Sweet Home 3D catalog piece is, in our terms: its NYU40 class, the category of our
// parametric furniture library (procedural/furniture.h, 63 categories) it stands in for, if
// any, and how it is placed. Decided from its name, then its Sweet Home 3D category and size,
// by the ordered rule table in catalog_labels.cpp (documented in docs/assets.md).
#include <string>

#include "assets/furniture_catalog.h"

namespace inet {

struct CatalogLabel {
  int nyu40 = 40;        ///< 1..40
  std::string category;  ///< one of furnitureCategories(), or "" (no parametric equivalent)
  std::string kind;      ///< fine-grained name for Object::kind: `category`, else the name
  /// The piece fills `category`'s place without being one (a teapot where a mug would stand,
  /// a toy where a vase would): its kind is its own name, and a furnisher places it by the
  /// small-prop rule (any small thing on a support) rather than by the category's sizes.
  bool slot = false;
  std::string rule;      ///< the rule that decided ("name 'sofa'", "default: large"), for docs
};

/// The label of `piece` (deterministic; never fails: an unmatched piece is otherprop, or
/// otherfurniture when its largest side exceeds 1 m).
CatalogLabel labelCatalogPiece(const CatalogPiece& piece);

}  // namespace inet
