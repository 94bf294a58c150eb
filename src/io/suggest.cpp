// Edit distance and closest-candidate search behind every "did you mean" hint.
#include "io/suggest.h"

#include <algorithm>
#include <cctype>

namespace penumbra {

namespace {

// Longer words never get a suggestion: the O(n*m) table would let a hostile
// scene with megabyte-long keys stall the loader, and no typo is that long.
constexpr size_t kMaxSuggestLength = 64;

char fold(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

size_t sharedPrefix(const std::string& a, const std::string& b) {
  size_t n = 0;
  while (n < a.size() && n < b.size() && fold(a[n]) == fold(b[n])) ++n;
  return n;
}

}  // namespace

int editDistance(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  // Three rolling rows: the transposition case looks two rows back.
  std::vector<int> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (size_t j = 0; j <= m; ++j) prev[j] = static_cast<int>(j);
  for (size_t i = 1; i <= n; ++i) {
    cur[0] = static_cast<int>(i);
    for (size_t j = 1; j <= m; ++j) {
      int cost = fold(a[i - 1]) == fold(b[j - 1]) ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && fold(a[i - 1]) == fold(b[j - 2]) &&
          fold(a[i - 2]) == fold(b[j - 1])) {
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
      }
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
  if (word.empty() || word.size() > kMaxSuggestLength) return {};
  std::string best;
  int bestDistance = 3;
  for (const std::string& c : candidates) {
    if (c.size() > kMaxSuggestLength) continue;
    int d = editDistance(word, c);
    if (d < bestDistance && d < static_cast<int>(c.size())) {
      best = c;
      bestDistance = d;
    }
  }
  if (!best.empty()) return best;
  size_t bestPrefix = 2;
  for (const std::string& c : candidates) {
    size_t p = sharedPrefix(word, c);
    if (p > bestPrefix) {
      best = c;
      bestPrefix = p;
    }
  }
  return best;
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
  std::string match = closestMatch(word, candidates);
  if (match.empty()) return {};
  return " (did you mean \"" + match + "\"?)";
}

}  // namespace penumbra
