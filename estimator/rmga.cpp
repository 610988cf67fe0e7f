// RM-GA evolution. Everything is sized at construction; a generation allocates nothing.
#include "estimator/rmga.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::estimator {

Rmga::Rmga(const GaParams& params, const GeneCodec& codec, const MarkerFitness& fitness,
           std::uint64_t seed)
    : params_(params), codec_(codec), fitness_(fitness), rng_(seed) {
  const int n = std::max(2, params_.population);
  population_.resize(static_cast<std::size_t>(n));
  survivors_ = std::clamp(static_cast<int>(std::lround(params_.selection_rate * n)),
                          std::max(2, params_.elite_count), n);
  rank_cdf_.resize(static_cast<std::size_t>(survivors_));
  double total = 0.0;
  for (int i = 0; i < survivors_; ++i) {
    total += survivors_ - i;  // the best survivor weighs survivors_, the last 1
    rank_cdf_[i] = total;
  }
  for (double& c : rank_cdf_) c /= total;
  randomise();
}

void Rmga::randomise() {
  std::uniform_int_distribution<int> field(0, kFieldMax);
  for (Individual& ind : population_) {
    for (auto& f : ind.gene.field) f = static_cast<std::uint16_t>(field(rng_));
    ind.fitness = 0.0;
  }
}

void Rmga::sort() {
  std::sort(population_.begin(), population_.end(),
            [](const Individual& a, const Individual& b) { return a.fitness > b.fitness; });
}

void Rmga::evaluate_all() {
  for (Individual& ind : population_) ind.fitness = fitness_.evaluate(codec_.decode(ind.gene));
  evaluations_ += static_cast<long>(population_.size());
  sort();
}

int Rmga::pick_parent() {
  const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  const auto it = std::lower_bound(rank_cdf_.begin(), rank_cdf_.end(), u);
  return static_cast<int>(std::min<std::ptrdiff_t>(it - rank_cdf_.begin(), survivors_ - 1));
}

void Rmga::generation() {
  const int n = static_cast<int>(population_.size());
  std::uniform_int_distribution<int> cut(0, kGeneBits);
  std::uniform_int_distribution<int> bit(0, kBitsPerField - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = survivors_; i < n; i += 2) {
    const int a = pick_parent();
    int b = pick_parent();
    if (b == a) b = (a + 1) % survivors_;
    int c1 = cut(rng_), c2 = cut(rng_);
    if (c1 > c2) std::swap(c1, c2);
    Gene child_a, child_b;
    two_point_crossover(population_[a].gene, population_[b].gene, c1, c2, child_a, child_b);
    population_[i].gene = child_a;
    if (i + 1 < n) population_[i + 1].gene = child_b;
  }
  for (int i = survivors_; i < n; ++i) {
    Individual& child = population_[i];
    if (unit(rng_) < params_.mutation_rate) {
      for (int f = 0; f < kGeneFields; ++f) flip_bit(child.gene, f * kBitsPerField + bit(rng_));
    }
    child.fitness = fitness_.evaluate(codec_.decode(child.gene));
  }
  evaluations_ += n - survivors_;
  sort();
}

void Rmga::insert(const Gene& gene, double fitness) {
  population_.back() = {gene, fitness};
  sort();
}

}  // namespace rovctl::estimator
