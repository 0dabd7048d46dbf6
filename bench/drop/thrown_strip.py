"""The coarse notched strip thrown against its held edge (issue 48, ply damage
forces): `python3 bench/drop/thrown_strip.py SPEED DURATION STEPS,... FORCES,... [VISCOSITY]`
from the repository root after `cargo build --release`, e.g.
`python3 bench/drop/thrown_strip.py 170 2e-5 1000,4000 newmark,implicit`; writes the
models and their runs in the working directory and prints per run: the impact energy
T0, the largest step rise of T + E_el (of T0), the damage (of T0; FT of G_FT A), the
scheme's dissipation, the ledger's rest (plastic), the end kinetic energy and the
balance. Results: bench/drop/damage_results.txt."""
import csv,json,subprocess,sys
src=open('examples/notched_strip_coarse.toml').read()
B='target/release/cufem'
def make(v, forces, steps, dur, visc="0.0", name="x", gamma=None):
    t=src.replace('name = "im7_8552"','name = "im7_8552"\ndensity = 1580.0',1)
    t=t.replace('viscosity = 1e-3','viscosity = '+visc,1)
    t=t.replace('increments = 150','increments = %d'%steps,1)
    t=t.replace('max_increment = 0.001\n','',1)
    i=t.index('[[constraints]]\nname = "pull"'); j=t.index('[[constraints]]',i+5); t=t[:i]+t[j:]
    t+='\n[analysis]\ntype = "transient"\nduration = %g\nply_damage_forces = "%s"\ninitial_velocities = [{ body = "strip", velocity = [%g, 0.0, 0.0] }]\n'%(dur,forces,v)
    if gamma: t+='newmark = { beta = %g, gamma = %g }\n'%(0.25*(gamma+0.5)**2,gamma)
    open(name+'.toml','w').write(t)
def run(name):
    r=subprocess.run([B,'run',name+'.toml','--out','out_'+name,'--quiet'],capture_output=True,text=True)
    if r.returncode: print(name,'FAILED',r.stderr[-300:]); return
    rows=list(csv.DictReader(open(f'out_{name}/energy.csv')))
    k=lambda r,c: float(r[c+'_J'])
    T0=k(rows[0],'kinetic')
    dmg=lambda r: sum(k(r,'damage_'+m) for m in ['fibre_tension','fibre_compression','matrix_tension','matrix_compression'])
    E=[k(r,'kinetic')+k(r,'elastic') for r in rows]
    rise=max(E[i+1]-E[i] for i in range(len(E)-1))/T0
    last=rows[-1]
    s=json.load(open(f'out_{name}/summary.json'))
    print(f"{name:28s} T0 {T0:.4f} rise {rise:.2e} D {dmg(last)/T0:.4f} (FT {k(last,'damage_fibre_tension')/0.63984:.4f} GA) scheme {k(last,'damage_scheme')/T0:.4f} plastic {k(last,'plastic')/T0:+.4f} T_end {k(last,'kinetic')/T0:.4f} bal {k(last,'balance')/T0:.1e}", flush=True)
if __name__=='__main__':
    v=float(sys.argv[1]); dur=float(sys.argv[2])
    for steps in map(int,sys.argv[3].split(',')):
        for f in sys.argv[4].split(','):
            n=f'v{v:g}_{f}_{steps}'; make(v,f,steps,dur,name=n,visc=sys.argv[5] if len(sys.argv)>5 else "0.0"); run(n)

def creation(name):
    rows=list(csv.DictReader(open(f'out_{name}/energy.csv')))
    k=lambda r,c: float(r[c+'_J'])
    E=[k(r,'kinetic')+k(r,'elastic') for r in rows]
    return sum(max(0,E[i+1]-E[i]) for i in range(len(E)-1))/E[0]
