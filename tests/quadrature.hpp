#pragma once
// The tests' independent reference quadrature: 20-point Gauss-Legendre on equal panels.
#include <functional>

namespace wr_test {

// int_a^b f by Gauss-Legendre (20 points) on `panels` equal panels.
inline double gauss_legendre(const std::function<double(double)>& f, double a, double b, int panels) {
  static const double x[10] = {0.0765265211334973, 0.2277858511416451, 0.3737060887154195, 0.5108670019508271,
                               0.6360536807265150, 0.7463319064601508, 0.8391169718222188, 0.9122344282513259,
                               0.9639719272779138, 0.9931285991850949};
  static const double w[10] = {0.1527533871307258, 0.1491729864726037, 0.1420961093183820, 0.1316886384491766,
                               0.1181945319615184, 0.1019301198172404, 0.0832767415767048, 0.0626720483341091,
                               0.0406014298003869, 0.0176140071391521};
  double sum = 0;
  const double h = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    const double m = a + (p + 0.5) * h, r = h / 2;
    for (int i = 0; i < 10; ++i) sum += r * w[i] * (f(m - r * x[i]) + f(m + r * x[i]));
  }
  return sum;
}

}  // namespace wr_test
