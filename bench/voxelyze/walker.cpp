// The same 3D walker as `cargo run --release -p vsrlab-physics3d --example walker3d`, on
// Voxelyze built from its public source: a 4 x 3 x 2 slab on four 1-voxel legs of the affordance
// study's material (E 1e4 Pa, 10 kg/m^3, CTE 0.01, friction 1 / 0.5, damping 1 / 0.01 / 0.8),
// 1 cm voxels, gravity and floor on, every voxel's temperature 14.4714 sin(2 pi 2 t - pi x / 2),
// dt 0.95 of the recommended step. Prints the centre's displacement and voxel-steps per CPU-second.
// Arguments: seconds (2), body (`quadruped`, or `box6`: a 6 x 6 x 6 box), collisions (`off`, or
// `on`: Voxelyze's own voxel-voxel collisions).
#include "Voxelyze.h"
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

int main(int argc, char** argv) {
    double seconds = argc > 1 ? atof(argv[1]) : 2.0;
    bool box = argc > 2 && strcmp(argv[2], "box6") == 0;
    bool collisions = argc > 3 && strcmp(argv[3], "on") == 0;
    CVoxelyze vx(0.01);
    CVX_Material* m = vx.addMaterial(1e4f, 10.0f);
    m->setCte(0.01f);
    m->setStaticFriction(1.0f);
    m->setKineticFriction(0.5f);
    m->setInternalDamping(1.0f);
    m->setGlobalDamping(0.01f);
    m->setCollisionDamping(0.8f);
    vx.setGravity(1.0f);
    vx.enableFloor(true);
    if (collisions) vx.enableCollisions(true);
    std::vector<CVX_Voxel*> voxels;
    std::vector<int> column;
    if (box) {
        for (int x = 0; x < 6; x++)
            for (int y = 0; y < 6; y++)
                for (int z = 0; z < 6; z++) {
                    voxels.push_back(vx.setVoxel(m, x, y, z));
                    column.push_back(x);
                }
    } else {
        for (int x = 0; x < 4; x++)
            for (int y = 0; y < 3; y++)
                for (int z = 1; z < 3; z++) {
                    voxels.push_back(vx.setVoxel(m, x, y, z));
                    column.push_back(x);
                }
        int legs[4][2] = {{0, 0}, {0, 2}, {3, 0}, {3, 2}};
        for (auto& l : legs) {
            voxels.push_back(vx.setVoxel(m, l[0], l[1], 0));
            column.push_back(l[0]);
        }
    }
    auto centre = [&]() {
        double c[3] = {0, 0, 0};
        for (auto* v : voxels) {
            c[0] += v->position().x;
            c[1] += v->position().y;
            c[2] += v->position().z;
        }
        for (double& k : c) k /= voxels.size();
        return std::vector<double>{c[0], c[1], c[2]};
    };
    std::vector<double> start = centre();
    double dt = 0.95 * vx.recommendedTimeStep();
    long steps = (long)(seconds / dt);
    const double pi = 3.14159265358979323846;
    clock_t c0 = clock();
    for (long k = 0; k < steps; k++) {
        double t = k * dt;
        for (size_t i = 0; i < voxels.size(); i++)
            voxels[i]->setTemperature((float)(14.4714 * sin(2 * pi * 2 * t - pi * column[i] / 2.0)));
        if (!vx.doTimeStep((float)dt)) {
            printf("diverged at step %ld\n", k);
            return 1;
        }
    }
    double cpu = double(clock() - c0) / CLOCKS_PER_SEC;
    std::vector<double> end = centre();
    printf("Voxelyze (collisions %s): %zu voxels, %d links, dt %.4e s, %ld steps in %.2f s CPU: centre moved (%+.4f, %+.4f, %+.4f) m, %.0f voxel-steps/s\n",
           collisions ? "on" : "off", voxels.size(), vx.linkCount(), dt, steps, cpu, end[0] - start[0], end[1] - start[1], end[2] - start[2],
           voxels.size() * steps / cpu);
    return 0;
}
