// The skin-weight policy shared by every character reader: sums checked or
// normalized (WeightPolicy), vertices without weights given their nearest
// weighted vertex's.
#pragma once

#include "snh/character.h"

namespace snh::detail {

// Resolves c.weights (raw rows per surface vertex, as the file gives them)
// in place: rows summing to 1 within options.weight_tolerance are kept,
// others divided by their sum (WeightPolicy::normalize, one warning with the
// count and the worst sum) or refused (WeightPolicy::strict: snh::Error
// naming the file and the first such vertex); an empty row takes the row of
// the nearest vertex that has weights (one warning with the count). Rows
// come out sorted by joint. snh::Error when no vertex has a weight.
void resolve_skin_weights(Character& c, const CharacterReadOptions& options);

}  // namespace snh::detail
