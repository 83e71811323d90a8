/* Two C masters in one process, for python_tests/test_experiments_platforms.py and
 * python_tests/test_aarch64.py under qemu-aarch64: experiment_driver.c's replay of the reference
 * experiments, then fmu3_driver.c's life cycle and default scene, on the same loaded binary. The
 * FMU's discretization cache then builds a plate both use once (the default plate's modal basis:
 * ~28 s of emulated CPU per process); each master runs as it does alone (compiled with
 * -Dmain=experiment_driver_main and -Dmain=fmu3_driver_main), and the results are the same bits
 * (the cache gives a shared plate's results bit for bit, python_tests/test_discretization_cache.py).
 * The experiments go first: experiment_driver keeps the library loaded, so fmu3_driver's dlopen
 * finds it with its plates and its dlclose does not unload it.
 *
 *   driver_chain LIBRARY TOKEN PLAN OUT [PLAN OUT ...] -- LIBRARY TOKEN
 *
 * stdout is fmu3_driver's; stderr both masters' messages, then one line per master,
 * "driver_chain: experiment_driver exit N" and "driver_chain: fmu3_driver exit N". Exit 0 when both
 * exited 0, 1 otherwise (fmu3_driver runs whatever the experiments did). */
#include <stdio.h>
#include <string.h>

int experiment_driver_main(int argc, char** argv);
int fmu3_driver_main(int argc, char** argv);

int main(int argc, char** argv) {
    int split = 1;
    while (split < argc && strcmp(argv[split], "--") != 0) ++split;
    if (split == argc) {
        fprintf(stderr, "usage: driver_chain LIBRARY TOKEN PLAN OUT [PLAN OUT ...] -- LIBRARY TOKEN\n");
        return 2;
    }
    argv[split] = argv[0];
    const int experiments = experiment_driver_main(split, argv);
    fflush(stdout);
    const int life_cycle = fmu3_driver_main(argc - split, argv + split);
    fflush(stdout);
    fprintf(stderr, "driver_chain: experiment_driver exit %d\ndriver_chain: fmu3_driver exit %d\n", experiments,
            life_cycle);
    return experiments == 0 && life_cycle == 0 ? 0 : 1;
}
