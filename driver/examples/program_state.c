/* SPDX-License-Identifier: Apache-2.0 */
/* The programming sequence of docs/driver.md: GL's default state on the gl_default core, a shiny material and
 * GL_LIGHT0 from (1, 1, 1), as the (address, data) words a driver hands to the core's register port (reg_we_i,
 * reg_addr_i, reg_data_i while reg_ready_o). ctest driver.example runs it. */
#include <stdio.h>

#include "shadecore_light_driver.h"

int main(void) {
  sc_light_config cfg;
  sc_light_state st;
  sc_light_write w[SC_LIGHT_MAX_STATE_WRITES];
  sc_light_writes buf;
  size_t i;
  int e;
  if ((e = sc_light_config_named("gl_default", &cfg)) || (e = sc_light_state_defaults(&cfg, &st))) return 1;
  st.material.specular[0] = st.material.specular[1] = st.material.specular[2] = 0.8;
  st.material.shininess = 128;
  st.num_lights = 1; /* GL_LIGHT0 enabled: a directional light towards (1, 1, 1) */
  st.lights[0].position[0] = st.lights[0].position[1] = st.lights[0].position[2] = 1.0;
  sc_light_writes_init(&buf, w, SC_LIGHT_MAX_STATE_WRITES);
  if ((e = sc_light_state_writes(&cfg, &st, &buf))) {
    fprintf(stderr, "program_state: %s\n", sc_light_strerror(e));
    return 1;
  }
  for (i = 0; i < buf.count; ++i) printf("0x%03x 0x%08x\n", (unsigned)w[i].addr, (unsigned)w[i].data);
  printf("%u register writes\n", (unsigned)buf.count);
  return 0;
}
