#pragma once
// Choice of delay and dimension (docs/analysis.md#embedding): average mutual
// information (AMI), autocorrelation, false nearest neighbours (Kennel's two
// criteria) and Cao's E1/E2.
#include <vector>

namespace cvt::analysis {

struct AmiResult {
  std::vector<double> ami;   // I(tau) in nats, tau = 0..max_lag
  std::vector<double> acf;   // autocorrelation, tau = 0..max_lag
  int tau_ami = 0;           // first local minimum of I (0 if none)
  int tau_acf_zero = 0;      // first zero crossing of the autocorrelation (0 if none)
  int tau = 1;               // chosen delay
  const char* method = "";   // "ami_first_minimum", "ami_1_over_e", "acf_zero" or "fallback_1"
  int bins = 0;
};
// bins = 0: choose from N (docs/analysis.md#ami).
AmiResult average_mutual_information(const std::vector<double>& x, int max_lag, int bins = 0);

struct FnnOptions {
  int tau = 1;
  int m_max = 10;
  double rtol = 10.0;       // Kennel criterion 1
  double atol = 2.0;        // Kennel criterion 2
  double threshold = 0.01;  // dimension = first m with fraction <= threshold
  int theiler = -1;         // -1: default_theiler(x)
};
struct FnnResult {
  std::vector<int> m;
  std::vector<double> fraction;       // either criterion
  std::vector<double> fraction_rtol;  // criterion 1 only
  std::vector<double> fraction_atol;  // criterion 2 only
  int dimension = 0;                  // first m with fraction <= threshold
  bool reached = false;               // false: threshold never reached, dimension = m_max
  int theiler = 0;
};
FnnResult false_nearest_neighbours(const std::vector<double>& x, const FnnOptions& opt);

struct CaoOptions {
  int tau = 1;
  int m_max = 10;
  double e1_threshold = 0.9;  // dimension = first m with E1(m) >= threshold
  int theiler = -1;
};
struct CaoResult {
  std::vector<int> m;
  std::vector<double> e1, e2;
  int dimension = 0;
  bool reached = false;
  int theiler = 0;
};
CaoResult cao(const std::vector<double>& x, const CaoOptions& opt);

}  // namespace cvt::analysis
