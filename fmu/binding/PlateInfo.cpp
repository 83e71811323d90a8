// The plate's fixed part of modelDescription.xml and its documentation page (fmu::ModelInfo): what
// the model is, its default scene, how to use it, what it refuses ({fmi2:…}/{fmi3:…}: one version's).
#include "binding/PlateVariables.h"

namespace plateimpact {

const fmu::ModelInfo& plateInfo() {
    static const fmu::ModelInfo info{
        "PlateImpact",
        "PlateImpact",
        "Kirchhoff plate clamped along x = 0 and free elsewhere, between two flat obstacles; C1 finite elements "
        "(Argyris or reduced FVS), Newmark scheme with exact per-step contact QP at a fixed time step dt",
        /*canInterpolateInputs=*/true,
        /*maxOutputDerivativeOrder=*/0,
        /*canGetAndSetFMUstate=*/true,
        /*defaultStopTime=*/0.2,
        /*defaultStepSize=*/0.001,
        R"(<h2>What it computes</h2>
<p>A Kirchhoff&ndash;Love plate [0, length] &times; [0, width], clamped along x = 0 and free elsewhere, between a flat
obstacle below (obstacle_lower) and one above (obstacle_upper). The master moves the clamped edge
(base_displacement) and may press on the plate (load, a uniform pressure). C1 finite elements (Argyris
triangles or reduced Fraeijs de Veubeke&ndash;Sander quadrilaterals), the Newmark scheme (gamma = 1/2, beta)
at the fixed internal step dt, and one exact contact QP per step keeping every mesh vertex between the
obstacles (Pozzolini, Renard &amp; Salaün 2013). Beyond the paper: a singular mass (mass = singular_p0)
whose impacts keep their energy as dt &rarr; 0, a restitution coefficient and Rayleigh damping.</p>
<h2>The default scene</h2>
<p>A 1.2 &times; 0.4 &times; 0.01 m steel plate (E = 210 GPa, &nu; = 0.3, &rho; = 7770 kg/m<sup>3</sup>),
14 &times; 5 cells (140 Argyris triangles), obstacles at &plusmn;0.1 m, dt = 1e-5 s; driven with
base_displacement = 0.09 sin(2&pi; 10 t) m it hits the obstacles from t &asymp; 0.05 s on.</p>
<h2>Using it</h2>
<ul>
<li>Any communication step up to a tenth of the plate's first period (T1/10: 0.0163 s for the default plate): the
scheme keeps its fixed grid of dt and interpolates the outputs between grid points; steps that are whole multiples
of dt (relative tolerance 1e-9) run exactly on the grid. A longer step over which an input changed is warned of
once: its samples cannot carry what the input does at the plate's frequencies.</li>
<li>Inputs: {fmi2:give their first and second derivatives (fmiXSetRealInputDerivatives) when you can; otherwise
}the FMU {fmi2:extrapolates}{fmi3:holds or extrapolates} the communicated values (base_input_mode, load_input_mode).</li>
<li>Switches (element, mass, base_drive, base_input_mode, load_input_mode) are Integers: the description of each
lists its items, e.g. base_drive = 2 drives the clamp by base_velocity.</li>
{fmi3:<li>Early return: a master that grants it at fmiXInstantiateCoSimulation gets every contact onset and
release as an event, exactly on the internal grid (lastSuccessfulTime), the impact in the outputs there.</li>
<li>The array output vertex_displacement holds the deflection at every mesh vertex
([vertex_output][vertices_x][vertices_y]); vertices_x = nx + 1 and vertices_y = ny + 1 are views of nx and ny;
vertex_output = 0 (before initialization) leaves the array empty.</li>
<li>Terminals (terminalsAndIcons/terminalsAndIcons.xml): <code>clamp</code> (kind
org.plateimpact.TranslationalFlange, matchingRule bus: base_displacement s, base_velocity v, base_acceleration a
in, clamp_force f out), <code>armature</code> (the same kind, plug: drive_force f in, clamp_displacement s,
clamp_velocity v, clamp_acceleration a out) and <code>line</code> (kind org.plateimpact.TransmissionLineEnd,
matchingRule org.plateimpact.crossed: tlm_wave_in wave_in, tlm_wave_out wave_out, tlm_impedance impedance; one
end's wave_out feeds the other's wave_in, the impedances are equal). A TranslationalFlange's members connect by
memberName, each output to the partner's input of the same memberName (all are signals: the connection is
causal).</li>
}<li>Outputs are absolute displacements; the energy ledger energy = E0 + energy_input &minus; energy_dissipated
&minus; energy_damped holds to roundoff.</li>
</ul>
<p>Reference experiments to validate this FMU on your platform and master (FMI-LS-REF):
<a href="fmi-ls-ref.html">fmi-ls-ref.html</a>.</p>
<h2>Limits: what the FMU refuses</h2>
<p>Each refusal returns fmiXError and logs what was wrong and the allowed range (category logStatusError).
Parameters outside the min/max of the table below (poisson_ratio and the obstacles' heights exclude their ends:
0 &lt; poisson_ratio &lt; 0.5, obstacle_lower &lt; 0 &lt; obstacle_upper); beta &lt; 0.25 beyond the stability
bound on dt; a singular mass with modes &gt; 0, beta &lt; 0.25 or without massless directions at every contact
vertex; an instance whose estimated memory exceeds memory_limit; inputs outside their min/max, NaN or Inf; a
clamp driven past an obstacle; a communication step shorter than 1e-9 dt; calls outside the states FMI
{fmi2:2.0}{fmi3:3.0} allows; FMU states of another build, of another CPU architecture (both platforms named) or damaged (XXH64 checksum); time_scheme = conserving
with mass = consistent or restitution &gt; 0. With the clamp carried (base_drive = force: an armature inside the
FMU; tlm: the end of a transmission line to a partner FMU): armature_mass &le; 0, tlm_impedance &le; 0, a singular
mass, a second input driving the clamp (a motion input with force or tlm, a drive_force with a motion drive),
communication steps that are not whole multiples of dt.</p>
)",
        /*stateMagic=*/"PLATEIMP",
    };
    return info;
}

}  // namespace plateimpact
