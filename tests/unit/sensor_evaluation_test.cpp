// evaluate_sensors runs every cycle: it must not allocate (docs/sensors.md). Counted with a
// replacement of the global operator new that only counts while a test asks it to.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>

#include "element/kernels.hpp"
#include "io/keyword/reader.hpp"
#include "sensor/sensor.hpp"
#include "sensor/sensor_output.hpp"
#include "solver/build_state.hpp"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace {

TEST(SensorEvaluation, DoesNotAllocate) {
  const std::string deck =
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
      "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\np\n1,1,1\n*SECTION_SOLID\n1,1\n"
      "*MAT_ELASTIC\n1,1.0,100.0,0.3\n*DEFINE_VECTOR\n3,0,0,0,0,0,1\n"
      "*SENSOR_DEFINE_NODE\n1,7,0,3,,COORD\n2,7,1,0,,VEL\n3,7,0,3,,ACC\n"
      "*SENSOR_DEFINE_ELEMENT\n4,SOLID,1,VM,STRESS\n5,SOLID,1,XX,STRAIN\n"
      "*DEFINE_FUNCTION\n500\nf(a,b)=a*b+sin(time)\n*SENSOR_DEFINE_FUNCTION\n6,500,1,5\n"
      "*SENSOR_SWITCH\n601,,6,GT,0.5,,0.01\n602,TIME,,GT,0.02,,,0.01\n"
      "*SENSOR_SWITCH_CALC-LOGIC\n610,-601,-602\n"
      "*SENSOR_CONTROL\n701,DEF2RIG,5,,-1\nOFF,610,601\n";
  const auto model = rf::io::read_deck_text(deck, "alloc.k");
  const rf::solver::NodeIndex index(model);
  rf::solver::State state = rf::solver::build_state(model, index);
  rf::sensor::SensorSystem sys = rf::sensor::build_sensor_system(model, index, state);
  const auto path = std::filesystem::temp_directory_path() / "rigidflex_sensor_alloc.csv";
  rf::sensor::SensorCsv csv(path, 1e-3);
  state.dt = 1e-3;
  // Warm up: the first evaluation and the first output may size their buffers.
  rf::sensor::evaluate_sensors(sys, state, 0.0);
  csv.write(sys, true);
  // The counter counts (a direct call of operator new cannot be elided).
  static void* volatile sink = nullptr;
  allocations = 0;
  counting = true;
  sink = ::operator new(8);
  counting = false;
  ::operator delete(sink);
  ASSERT_EQ(allocations.load(), 1);

  allocations = 0;
  counting = true;
  for (int n = 1; n <= 100; ++n) {
    for (std::size_t i = 0; i < state.nodes.size(); ++i) {
      state.nodes.x.x[i] += 1e-3 * state.nodes.x0.x[i];  // stretch along x
      state.nodes.v.z[i] = 0.01 * n;
    }
    rf::sensor::evaluate_sensors(sys, state, n * 1e-3);
    csv.write(sys, false);
  }
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
  EXPECT_TRUE(rf::sensor::switch_status(sys, 610));
  EXPECT_GT(rf::sensor::sensor_value(sys, 5), 0.09);  // ln(1.1)
  std::filesystem::remove(path);
}

}  // namespace
