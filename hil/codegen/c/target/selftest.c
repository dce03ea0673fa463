/* The C codec on Cortex-M4F under the no-heap link check (docs/can.md#c-codec):
 * every message encoded at its initial values and at a second set, protected,
 * received through the bank (in order, repeated, bad CRC), decoded back.
 * Returns the number of failed checks. */
#include "cvtplant_c/can_messages.h"

int cvt_can_c_selftest(void);

int cvt_can_c_selftest(void) {
  int failures = 0;
  cvt_can_rx_bank bank;
  cvt_can_rx_bank_init(&bank);
  for (unsigned i = 0; i < CVT_CAN_MESSAGE_COUNT; ++i) {
    const cvt_can_message_info* info = &cvt_can_messages[i];
    cvt_can_any a;
    a.which = (cvt_can_message_id)i;
    cvt_can_any_init(&a);
    cvt_e2e_protector p;
    cvt_e2e_protector_init(&p, info->e2e_data_id);
    for (int k = 0; k < 3; ++k) {
      cvt_can_frame f = {info->can_id, info->dlc, 0, {0}};
      if (cvt_can_any_pack(&a, f.data) != CVT_CODEC_OK) ++failures;
      cvt_e2e_protect(&p, f.data);
      cvt_can_any out;
      const cvt_rx_result r = cvt_can_rx_bank_receive(&bank, &f, &out);
      if (!cvt_rx_accepted(r) || out.which != a.which) ++failures;
      double x[8], y[8];
      cvt_can_any_get(&a, x);
      cvt_can_any_get(&out, y);
      for (unsigned s = 0; s < info->signal_count; ++s)
        if (x[s] != y[s]) ++failures;
      /* The same frame again is REPEATED; a flipped CRC bit WRONG_CRC. */
      if (cvt_can_rx_bank_receive(&bank, &f, &out).e2e != CVT_E2E_REPEATED) ++failures;
      f.data[0] ^= 0x10u;
      if (cvt_can_rx_bank_receive(&bank, &f, &out).e2e != CVT_E2E_WRONG_CRC) ++failures;
    }
  }
  /* A NaN is refused, never encoded. */
  cvt_ctrl_cmd c;
  cvt_ctrl_cmd_init(&c);
  c.clamp_force_cmd_N = 0.0f / 0.0f;
  uint8_t pl[8];
  if (cvt_ctrl_cmd_pack(&c, pl) != CVT_CODEC_NOT_FINITE) ++failures;
  return failures;
}
