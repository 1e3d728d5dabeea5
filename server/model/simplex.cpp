#include "model/simplex.h"

#include <algorithm>
#include <array>

#include <glm/geometric.hpp>

namespace shadelab::model {

glm::vec3 nelder_mead(const std::function<double(const glm::vec3&)>& f, const glm::vec3& start, float step, int iterations) {
  std::array<glm::vec3, 4> x = {start, start + glm::vec3(step, 0, 0), start + glm::vec3(0, step, 0), start + glm::vec3(0, 0, step)};
  std::array<double, 4> y;
  for (int i = 0; i < 4; ++i) y[i] = f(x[i]);
  for (int it = 0; it < iterations; ++it) {
    std::array<int, 4> order = {0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return y[a] < y[b]; });
    const int best = order[0], worst = order[3], second = order[2];
    const glm::vec3 centre = (x[order[0]] + x[order[1]] + x[order[2]]) / 3.0f;
    const glm::vec3 reflected = centre + (centre - x[worst]);
    const double yr = f(reflected);
    if (yr < y[best]) {
      const glm::vec3 expanded = centre + 2.0f * (centre - x[worst]);
      const double ye = f(expanded);
      x[worst] = ye < yr ? expanded : reflected;
      y[worst] = std::min(ye, yr);
    } else if (yr < y[second]) {
      x[worst] = reflected, y[worst] = yr;
    } else {
      const glm::vec3 contracted = centre + 0.5f * (x[worst] - centre);
      if (const double yc = f(contracted); yc < y[worst]) {
        x[worst] = contracted, y[worst] = yc;
      } else {
        for (int i : {order[1], order[2], order[3]}) x[i] = x[best] + 0.5f * (x[i] - x[best]), y[i] = f(x[i]);
      }
    }
  }
  return x[static_cast<std::size_t>(std::min_element(y.begin(), y.end()) - y.begin())];
}

}  // namespace shadelab::model
