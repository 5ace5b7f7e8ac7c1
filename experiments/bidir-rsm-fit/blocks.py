"""8 x 8 block means of bidir / reference EXR layers (luminance), for run.sh.

  blocks.py ref  REF[+REF2..] LAYER RUN.exr...   block ratios run / reference: mean over the runs (seeds),
                                                 the seeds' standard error, z; image ratio
  blocks.py pair LAYER 'A-glob' 'B-glob'         block ratios mean(A) / mean(B) with the combined error
  blocks.py seeds REF[+REF2..] LAYER RUN.exr...  each run's block ratios (one line per seed)
EXRs are read through exrdump (exrdump.cpp beside this file, built on first use with g++ and OpenEXR).
"""
import glob, os, subprocess, sys
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DUMP = os.path.join(os.environ.get('TMPDIR', '/tmp'), 'bl-exrdump')


def load(path):
    if not os.path.exists(DUMP):
        flags = subprocess.check_output(['pkg-config', '--cflags', '--libs', 'OpenEXR']).decode().split()
        subprocess.check_call(['g++', '-O2', '-std=c++17', os.path.join(HERE, 'exrdump.cpp'), '-o', DUMP] + flags)
    out = path + '.bin'
    if not os.path.exists(out) or os.path.getmtime(out) < os.path.getmtime(path):
        subprocess.check_call([DUMP, path, out])
    with open(out, 'rb') as f:
        w, h, n = map(int, f.readline().split())
        names = [f.readline().decode().strip() for _ in range(n)]
        data = np.frombuffer(f.read(), dtype=np.float32).reshape(n, h, w)
    layers = {}
    for i, name in enumerate(names):
        layer, _, channel = name.rpartition('.')
        layers.setdefault(layer, {})[channel] = data[i]
    return {k: np.stack([v['R'], v['G'], v['B']], -1) for k, v in layers.items()}


def blocks(path, layer, b=8):
    img = load(path)[layer].astype(np.float64)
    lum = 0.2126 * img[..., 0] + 0.7152 * img[..., 1] + 0.0722 * img[..., 2]
    h, w = lum.shape
    return lum[:h // b * b, :w // b * b].reshape(h // b, b, w // b, b).mean(axis=(1, 3))


def reference(spec, layer):
    paths = spec.split('+')
    return sum(blocks(p, layer) for p in paths) / len(paths)


def show(name, a):
    print(' ' + name + ':')
    print(np.array2string(a, precision=3, suppress_small=True, max_line_width=200))


def main():
    np.set_printoptions(linewidth=200, precision=3, suppress=True)
    cmd = sys.argv[1]
    if cmd in ('ref', 'seeds'):
        ref = reference(sys.argv[2], sys.argv[3])
        runs = np.array([blocks(p, sys.argv[3]) for p in sys.argv[4:]])
        if cmd == 'seeds':
            for p, r in zip(sys.argv[4:], runs):
                print(os.path.basename(p), ' '.join(f'{v:.3f}' for v in (r / ref).ravel()))
            return
        s = len(runs)
        mean, se = runs.mean(0), runs.std(0, ddof=1) / np.sqrt(s)
        image = runs.sum((1, 2)) / ref.sum()
        print(f' {s} seeds, image ratio {image.mean():.4f} +- {image.std(ddof=1) / np.sqrt(s):.4f}'
              f' (seeds {image.min():.3f}..{image.max():.3f})')
        show('block ratios', mean / ref)
        show('stderr / reference', se / ref)
        show('z', (mean - ref) / np.maximum(se, 1e-30))
    elif cmd == 'pair':
        layer = sys.argv[2]
        a = np.array([blocks(p, layer) for p in sorted(glob.glob(sys.argv[3]))])
        b = np.array([blocks(p, layer) for p in sorted(glob.glob(sys.argv[4]))])
        ma, mb = a.mean(0), b.mean(0)
        ea, eb = a.std(0, ddof=1) / np.sqrt(len(a)), b.std(0, ddof=1) / np.sqrt(len(b))
        r = ma / mb
        er = r * np.hypot(ea / ma, eb / mb)
        ia, ib = a.sum((1, 2)), b.sum((1, 2))
        ri = ia.mean() / ib.mean()
        ei = ri * np.hypot(ia.std(ddof=1) / np.sqrt(len(a)) / ia.mean(), ib.std(ddof=1) / np.sqrt(len(b)) / ib.mean())
        print(f' {len(a)} vs {len(b)} seeds, image ratio {ri:.4f} +- {ei:.4f}')
        show('block ratios', r)
        show('stderr', er)
        show('z', (r - 1) / er)
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
