// CatadioptricAR Core: the edit distance of two words, for "did you mean ...?" suggestions (a
// misspelt scene key, a mistyped program option).
#ifndef catarEditDistance_h
#define catarEditDistance_h

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace catar
{
/// Levenshtein distance: the fewest insertions, deletions and substitutions that turn a into b.
/// Quadratic in the lengths (the words are short).
inline std::size_t EditDistance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
  {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t up = row[j];
      row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1) });
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// The candidate closest to `word` by EditDistance (the first of the closest) among those that
/// close(distance, candidate) accepts, or nullptr. Each caller keeps its own idea of close.
template<typename Close>
const std::string* Nearest(
  const std::string& word, const std::vector<std::string>& candidates, Close close)
{
  const std::string* nearest = nullptr;
  std::size_t best = 0;
  for (const std::string& candidate : candidates)
  {
    const std::size_t d = EditDistance(word, candidate);
    if ((!nearest || d < best) && close(d, candidate))
    {
      best = d;
      nearest = &candidate;
    }
  }
  return nearest;
}
} // namespace catar

#endif
