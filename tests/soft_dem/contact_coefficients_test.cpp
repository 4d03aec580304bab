// [3.4]-[3.5]: (e, t_c) -> (k_n, eta_n), against the model's table (T4.1) to 3 digits.
#include "soft_dem/contact_coefficients.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace granjet::dem {
namespace {

struct Row {
  double e, kn, eta_n;
};

TEST(ContactCoefficients, Eq3_4_Eq3_5_MatchTableT4_1) {
  for (const Row& row : {Row{0.75, 4.98e2, 2.88}, Row{0.80, 4.96e2, 2.23}, Row{0.90, 4.94e2, 1.05},
                         Row{0.99, 4.93e2, 0.101}}) {
    ContactSpec spec;
    spec.restitution = row.e;
    spec.contact_time = 0.1;
    const ContactCoefficients c = contact_coefficients(spec);
    SCOPED_TRACE(row.e);
    EXPECT_NEAR(c.kn / row.kn, 1.0, 0.5e-2);  // 3 significant digits
    EXPECT_NEAR(c.eta_n / row.eta_n, 1.0, 0.5e-2);
    EXPECT_DOUBLE_EQ(c.kt, 0.2 * c.kn);
    EXPECT_DOUBLE_EQ(c.eta_t, 0.5 * c.eta_n);
  }
}

TEST(ContactCoefficients, FrictionStudyAtTc005MatchesSpec) {
  ContactSpec spec;
  spec.contact_time = 0.05;
  const ContactCoefficients c = contact_coefficients(spec);
  EXPECT_NEAR(c.kn / 1.99e3, 1.0, 0.5e-2);
  EXPECT_NEAR(c.eta_n / 5.75, 1.0, 0.5e-2);
}

TEST(ContactCoefficients, InvertBackToTcAndE) {
  ContactSpec spec;
  spec.restitution = 0.6;
  spec.contact_time = 0.013;
  const ContactCoefficients c = contact_coefficients(spec);
  const BinaryCollision back = binary_collision(c.kn, c.eta_n);
  EXPECT_NEAR(back.contact_time, 0.013, 1e-15);
  EXPECT_NEAR(back.restitution, 0.6, 1e-14);
  // Overdamped: no rebound, so no (e, t_c).
  EXPECT_TRUE(std::isnan(binary_collision(1.0, 2.0).restitution));
}

}  // namespace
}  // namespace granjet::dem
