// The Real-time Multi-step GA (the paper's Sec. 2.3): a population of 72-bit genes kept across
// frames and evolved a few generations per frame, with elitism, rank selection with a selection
// rate, two-point crossover and mutation.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "estimator/estimator_params.hpp"
#include "estimator/gene_codec.hpp"
#include "estimator/marker_fitness.hpp"

namespace rovctl::estimator {

struct Individual {
  Gene gene;
  double fitness = 0.0;  // the fitness the GA ranks by (MarkerFitness::search_score)
};

class Rmga {
 public:
  // `reading` says what the paper leaves open (GaReading); throws std::invalid_argument on an
  // unknown value.
  Rmga(const GaParams& params, const GeneCodec& codec, const MarkerFitness& fitness,
       std::uint64_t seed, const GaReading& reading = first_ga_reading());

  void randomise();  // a fresh uniformly random population (fitness 0 until evaluated)
  // Re-evaluates every gene on the current images and sorts by fitness (a new frame).
  void evaluate_all();
  // One generation. Ranked (sorted) population: the elite_count best are kept as they are; the
  // top selection_rate * N survive; the rest are replaced by two-point crossover children of
  // survivors picked by linear rank weights; the children (or, reading non_elite, every gene
  // outside the elite) are mutated as the reading says. Changed genes (or, reading population,
  // all) are evaluated and the population re-sorted.
  void generation();
  // Replaces the worst gene (used to seed; the population stays sorted).
  void insert(const Gene& gene, double fitness);

  const Individual& best() const { return population_.front(); }
  const std::vector<Individual>& population() const { return population_; }
  long evaluations() const { return evaluations_; }

 private:
  enum class Mutation { per_child, per_field, per_bit };
  int pick_parent();
  void sort();
  // Returns whether the gene changed.
  bool mutate(Gene& gene);

  GaParams params_;
  Mutation mutation_ = Mutation::per_child;
  bool mutate_survivors_ = false;
  bool evaluate_population_ = false;
  const GeneCodec& codec_;
  const MarkerFitness& fitness_;
  std::mt19937_64 rng_;
  std::vector<Individual> population_;
  std::vector<double> rank_cdf_;  // cumulative linear-rank weights over the survivors
  int survivors_ = 2;
  int elites_ = 1;
  long evaluations_ = 0;
};

}  // namespace rovctl::estimator
