// anvil: the command-line program. Everything lives in libanvil.
#include <anvil/simulator/simulator.h>

int main(int argc, char **argv)
{
  return anvil::run_anvil(argc, argv);
}
