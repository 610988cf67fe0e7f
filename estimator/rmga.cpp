// RM-GA evolution. Everything is sized at construction; a generation allocates nothing.
#include "estimator/rmga.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rovctl::estimator {

Rmga::Rmga(const GaParams& params, const GeneCodec& codec, const MarkerFitness& fitness,
           std::uint64_t seed, const GaReading& reading)
    : params_(params), codec_(codec), fitness_(fitness), rng_(seed) {
  if (reading.mutation == "per_child") {
    mutation_ = Mutation::per_child;
  } else if (reading.mutation == "per_field") {
    mutation_ = Mutation::per_field;
  } else if (reading.mutation == "per_bit") {
    mutation_ = Mutation::per_bit;
  } else {
    throw std::invalid_argument("Rmga: unknown mutation reading '" + reading.mutation + "'");
  }
  if (reading.mutants != "children" && reading.mutants != "non_elite") {
    throw std::invalid_argument("Rmga: unknown mutants reading '" + reading.mutants + "'");
  }
  if (reading.evaluation != "children" && reading.evaluation != "population") {
    throw std::invalid_argument("Rmga: unknown evaluation reading '" + reading.evaluation + "'");
  }
  mutate_survivors_ = reading.mutants == "non_elite";
  evaluate_population_ = reading.evaluation == "population";
  const int n = std::max(2, params_.population);
  population_.resize(static_cast<std::size_t>(n));
  survivors_ = std::clamp(static_cast<int>(std::lround(params_.selection_rate * n)),
                          std::max(2, params_.elite_count), n);
  elites_ = std::clamp(params_.elite_count, 0, survivors_);
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
  for (Individual& ind : population_) {
    ind.fitness = fitness_.search_score(codec_.decode(ind.gene));
  }
  evaluations_ += static_cast<long>(population_.size());
  sort();
}

int Rmga::pick_parent() {
  const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  const auto it = std::lower_bound(rank_cdf_.begin(), rank_cdf_.end(), u);
  return static_cast<int>(std::min<std::ptrdiff_t>(it - rank_cdf_.begin(), survivors_ - 1));
}

bool Rmga::mutate(Gene& gene) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> bit(0, kBitsPerField - 1);
  const double rate = params_.mutation_rate;
  switch (mutation_) {
    case Mutation::per_child:
      // The draws in this order are the first reading's: the improved mode's runs stay identical.
      if (!(unit(rng_) < rate)) return false;
      for (int f = 0; f < kGeneFields; ++f) flip_bit(gene, f * kBitsPerField + bit(rng_));
      return true;
    case Mutation::per_field: {
      bool changed = false;
      for (int f = 0; f < kGeneFields; ++f) {
        if (unit(rng_) < rate) {
          flip_bit(gene, f * kBitsPerField + bit(rng_));
          changed = true;
        }
      }
      return changed;
    }
    case Mutation::per_bit: {
      if (!(rate > 0.0)) return false;
      if (rate >= 1.0) {
        for (int k = 0; k < kGeneBits; ++k) flip_bit(gene, k);
        return true;
      }
      // Gaps between flipped bits are geometric: a few draws per gene instead of 72.
      std::geometric_distribution<int> gap(rate);
      bool changed = false;
      for (int k = gap(rng_); k < kGeneBits; k += 1 + gap(rng_)) {
        flip_bit(gene, k);
        changed = true;
      }
      return changed;
    }
  }
  return false;
}

void Rmga::generation() {
  const int n = static_cast<int>(population_.size());
  std::uniform_int_distribution<int> cut(0, kGeneBits);
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
  long evaluated = 0;
  // Survivors mutate after breeding, so the children come from the ranked, unmutated parents.
  for (int i = elites_; i < survivors_; ++i) {
    Individual& ind = population_[i];
    const bool changed = mutate_survivors_ && mutate(ind.gene);
    if (changed || evaluate_population_) {
      ind.fitness = fitness_.search_score(codec_.decode(ind.gene));
      ++evaluated;
    }
  }
  if (evaluate_population_) {
    for (int i = 0; i < elites_; ++i) {
      population_[i].fitness = fitness_.search_score(codec_.decode(population_[i].gene));
    }
    evaluated += elites_;
  }
  for (int i = survivors_; i < n; ++i) {
    Individual& child = population_[i];
    mutate(child.gene);
    child.fitness = fitness_.search_score(codec_.decode(child.gene));
  }
  evaluations_ += evaluated + (n - survivors_);
  sort();
}

void Rmga::insert(const Gene& gene, double fitness) {
  population_.back() = {gene, fitness};
  sort();
}

}  // namespace rovctl::estimator
