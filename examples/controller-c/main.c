/* cvt-controller: the template controller on a SocketCAN interface
 * (docs/tutorial.md). Lock-step (default): one control period per
 * HarnessDemand of the harness (docs/sil.md#external-lockstep). Real time:
 * one period per fresh plant group, at most one per 5 ms and at least one
 * per 15 ms, on the latest HarnessDemand. Ends on SIGINT/SIGTERM or after
 * --duration-s, printing a JSON summary. Exit 0, 1 (interface), 2 (usage). */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "controller.h"
#include "cvtplant_c/socketcan.h"

static volatile sig_atomic_t g_stop = 0;
static void on_signal(int sig) {
  (void)sig;
  g_stop = 1;
}

static int64_t now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static int usage(const char* msg, const char* arg) {
  fprintf(stderr, "cvt-controller: %s%s (see --help)\n", msg, arg);
  return 2;
}

int main(int argc, char** argv) {
  const char* iface = "vcan0";
  int realtime = 0;
  double duration_s = 0.0;
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
      puts("usage: cvt-controller [--iface NAME] [--mode lockstep|realtime] [--duration-s S]\n"
           "The template CVT controller (examples/controller-c) on a SocketCAN interface.\n"
           "  --iface NAME     vcan0 (default), or a real interface such as can0\n"
           "  --mode M         lockstep (default): one control period per HarnessDemand of the\n"
           "                   harness; realtime: one per fresh plant group (5 to 15 ms apart)\n"
           "  --duration-s S   stop after S s (default 0: until SIGINT/SIGTERM)\n"
           "Exit 0, 1 (interface), 2 (usage).");
      return 0;
    }
    if (i + 1 >= argc) return usage("missing value for ", argv[i]);
    const char* v = argv[++i];
    if (!strcmp(argv[i - 1], "--iface")) {
      iface = v;
    } else if (!strcmp(argv[i - 1], "--mode")) {
      if (!strcmp(v, "realtime")) realtime = 1;
      else if (strcmp(v, "lockstep") != 0) return usage("--mode: expected lockstep or realtime, got ", v);
    } else if (!strcmp(argv[i - 1], "--duration-s")) {
      char* end = NULL;
      duration_s = strtod(v, &end);
      if (end == v || *end != '\0' || !(duration_s >= 0.0 && duration_s <= 1e6))
        return usage("--duration-s: expected seconds in [0, 1e6], got ", v);
    } else {
      return usage("unknown option ", argv[i - 1]);
    }
  }
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  cvt_socketcan bus;
  if (cvt_socketcan_open(&bus, iface) != 0) {
    fprintf(stderr, "cvt-controller: %s: %s\n", iface, cvt_socketcan_error(&bus));
    cvt_socketcan_close(&bus);
    return 1;
  }
  static controller c;
  controller_init(&c);
  const int64_t t0 = now_ns(), end = t0 + (int64_t)(duration_s * 1e9);
  int64_t last_step = 0;
  uint32_t tx_failed = 0;
  while (!g_stop && (duration_s == 0.0 || now_ns() < end)) {
    cvt_can_frame f;
    const cvt_can_io_status st = cvt_socketcan_receive(&bus, &f, 1000000);
    if (st == CVT_CAN_IO_OK) controller_receive(&c, &f);
    else if (st != CVT_CAN_IO_TIMEOUT && st != CVT_CAN_IO_ERROR_FRAME) continue;
    int due;
    if (!realtime) {
      due = c.demand_pending;
    } else {
      const int64_t now = now_ns(), since = now - last_step;
      due = (controller_fresh_group(&c) && since >= 5000000) || since >= 15000000;
      if (due) last_step = now;
    }
    if (!due) continue;
    cvt_can_frame out[2];
    const int n = controller_step(&c, out);
    for (int k = 0; k < n; ++k)
      if (cvt_socketcan_send(&bus, &out[k]) != CVT_CAN_IO_OK) ++tx_failed;
  }
  const cvt_can_io_counters io = cvt_socketcan_counters(&bus);
  printf("{\"mode\": \"%s\", \"runs\": %u, \"periods\": %u, \"fresh_periods\": %u, \"accepted\": %u, "
         "\"rejected\": %u, \"tx_failed\": %u, \"rx_kernel_drops\": %llu, \"have_plant_params\": %s}\n",
         realtime ? "realtime" : "lockstep", c.runs, c.periods, c.fresh_periods, c.accepted, c.rejected, tx_failed,
         (unsigned long long)io.rx_kernel_drops, c.have_params ? "true" : "false");
  cvt_socketcan_close(&bus);
  return 0;
}
