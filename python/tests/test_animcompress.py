# SPDX-License-Identifier: Apache-2.0
"""The animcompress module against the animc command line and a real sequence of tests/data.

ctest (python_module) sets PYTHONPATH to the built module, ANIMC_CLI to the animc executable
and ANIMC_TEST_DATA to tests/data."""
import importlib.util
import json
import os
import pathlib
import subprocess
import sys
import threading

import numpy as np
import pytest

import animcompress

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = pathlib.Path(os.environ.get('ANIMC_TEST_DATA', ROOT / 'tests' / 'data'))
SEQUENCE = 'sydney_md2'  # 342 vertices x 198 frames: real motion, and quick


def load_bench_module(name):
    """bench/NAME.py (pc2: the project's one PC2 reader, ply: its PLY one), imported by path
    (bench is no package)."""
    spec = importlib.util.spec_from_file_location(name, ROOT / 'bench' / f'{name}.py')
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


pc2 = load_bench_module('pc2')
ply = load_bench_module('ply')


@pytest.fixture(scope='module')
def sequence():
    folder = DATA / SEQUENCE
    if not folder.is_dir():
        pytest.skip(f'no {SEQUENCE} in {DATA} (the folder searched; set ANIMC_TEST_DATA)')
    frames, _header = pc2.read_pc2(str(folder / f'{SEQUENCE}.pc2.xz'))
    faces = ply.read_ply_faces(folder / f'{SEQUENCE}.ply')
    return {'frames': np.ascontiguousarray(frames), 'faces': faces, 'folder': folder}


@pytest.fixture(scope='module')
def cli():
    path = os.environ.get('ANIMC_CLI')
    if not path or not os.path.exists(path):
        pytest.skip('ANIMC_CLI does not name the animc executable')
    return path


@pytest.fixture(scope='module')
def grouped(sequence):
    """The sequence coded with an intra frame every 10 frames, for random access."""
    return animcompress.encode(sequence['frames'], sequence['faces'], iframe_interval=10, max_error=0.01)


def cli_flags(codec, options):
    flags = ['--codec', codec]
    for name, value in options.items():
        flag = '--' + name.replace('_', '-')
        flags += [flag] if value is True else [flag, str(value)]
    return flags


def test_version_and_codecs():
    assert animcompress.__version__.count('.') == 2
    assert {'affine-octree', 'wavelet', 'trajectory', 'auto', 'trajectory2'} <= set(animcompress.codecs())


def test_affine_octree_round_trip_stays_within_the_bound(sequence):
    data = animcompress.encode(sequence['frames'], sequence['faces'], max_error=0.01)
    frames, faces = animcompress.decode(data)
    assert frames.dtype == np.float32 and frames.shape == sequence['frames'].shape
    assert faces.dtype == np.uint32 and np.array_equal(faces, sequence['faces'])
    m = animcompress.compare(sequence['frames'], frames)
    assert m['max_error_rel_cube'] <= 0.01 + 1e-6
    assert 0 < m['max_error'] == pytest.approx(np.linalg.norm(frames - sequence['frames'], axis=2).max(), rel=1e-5)
    assert m['frames'] == len(frames) and m['vertices'] == frames.shape[1]
    assert m['per_frame']['rms'].shape == m['per_frame']['max'].shape == (len(frames),)
    assert m['per_frame']['max'].max() == pytest.approx(m['max_error'])
    assert len(data) < sequence['frames'].nbytes / 5  # it did compress


def test_compare_with_faces_gives_animc_compares_sted(sequence, cli, tmp_path):
    data = animcompress.encode(sequence['frames'], sequence['faces'], max_error=0.01)
    decoded = animcompress.decode(data)[0]
    assert 'sted' not in animcompress.compare(sequence['frames'], decoded)
    m = animcompress.compare(sequence['frames'], decoded, faces=sequence['faces'])
    (tmp_path / 'x.ams').write_bytes(data)
    folder = sequence['folder']
    out = subprocess.run([cli, 'compare', str(folder / f'{SEQUENCE}.pc2.xz'), str(tmp_path / 'x.ams'),
                          '--mesh', str(folder / f'{SEQUENCE}.ply'), '--json'],
                         check=True, capture_output=True, text=True).stdout
    expected = json.loads(out)
    assert m['sted'] > 0 and m['sted_spatial'] > 0 and m['sted_temporal'] > 0
    for key in ('sted', 'sted_spatial', 'sted_temporal'):
        assert m[key] == pytest.approx(expected[key], rel=1e-9)
    assert animcompress.compare(sequence['frames'], sequence['frames'], faces=sequence['faces'])['sted'] == 0


def test_wavelet_target_kg_bounds_the_sequence_error(sequence):
    # docs/wavelet.md: each frame's float output error is kept under the target's share, so
    # the sequence KG error is at most the target (a small step lets the target be reached).
    data = animcompress.encode(sequence['frames'], sequence['faces'], codec='wavelet', target_kg=0.5, step=1e-5)
    assert animcompress.info(data)['codec'] == 'wavelet'
    m = animcompress.compare(sequence['frames'], animcompress.decode(data)[0])
    assert 0 < m['kg_error'] <= 0.5


def test_trajectory_target_kg_bounds_the_sequence_error(sequence):
    data = animcompress.encode(sequence['frames'], sequence['faces'], codec='trajectory', target_kg=0.3)
    assert animcompress.info(data)['codec'] == 'trajectory'
    m = animcompress.compare(sequence['frames'], animcompress.decode(data)[0])
    assert 0.2 < m['kg_error'] <= 0.3


@pytest.mark.parametrize('codec, options', [
    ('affine-octree', {'max_error': 0.01}),
    ('affine-octree', {'max_error': 0.005, 'profile': 'paper', 'iframe_interval': 20}),
    ('wavelet', {'target_kg': 0.5, 'step': 1e-05, 'iframe_interval': 50}),
    ('wavelet', {'step': 0.001, 'i_frames_only': True}),
    ('trajectory', {'target_kg': 0.5}),
    ('trajectory', {'step': 0.001, 'group_frames': 30, 'iframe_interval': 50}),
    ('trajectory', {'max_error': 0.01}),
    ('trajectory2', {'target_kg': 0.3, 'parts': 4}),
    ('auto', {'max_error': 0.01, 'iframe_interval': 2}),
    ('auto', {'target_kg': 0.5}),
])
def test_bytes_and_frames_equal_the_command_line(sequence, cli, tmp_path, codec, options):
    ams, pc2_out = tmp_path / 'out.ams', tmp_path / 'out.pc2'
    stem = sequence['folder'] / SEQUENCE
    subprocess.run([cli, 'encode', f'{stem}.pc2.xz', '--mesh', f'{stem}.ply', '-o', str(ams)]
                   + cli_flags(codec, options), check=True, capture_output=True)
    data = animcompress.encode(sequence['frames'], sequence['faces'], codec=codec, **options)
    assert data == ams.read_bytes()
    subprocess.run([cli, 'decode', str(ams), '-o', str(pc2_out)], check=True, capture_output=True)
    cli_frames, _header = pc2.read_pc2(str(pc2_out))
    assert np.array_equal(animcompress.decode(data)[0], cli_frames)


@pytest.mark.parametrize('codec, options', [
    ('affine-octree', {'max_error': 0.01, 'iframe_interval': 40}),
    ('trajectory', {'target_kg': 0.3, 'iframe_interval': 50}),
    ('trajectory2', {'target_kg': 0.3, 'iframe_interval': 50}),
    ('auto', {'max_error': 0.01}),
])
def test_threads_change_neither_bytes_nor_frames(sequence, codec, options):
    args = (sequence['frames'], sequence['faces'])
    one = animcompress.encode(*args, codec=codec, threads=1, **options)
    assert animcompress.encode(*args, codec=codec, threads=2, **options) == one
    assert animcompress.encode(*args, codec=codec, **options) == one  # threads=0: one per core
    frames = animcompress.decode(one, threads=1)[0]
    assert np.array_equal(animcompress.decode(one, threads=3)[0], frames)
    assert np.array_equal(animcompress.decode(one, range(30, 120), threads=2)[0], frames[30:120])
    assert np.array_equal(animcompress.open(one, threads=2)[77], frames[77])
    with pytest.raises(ValueError, match='threads'):
        animcompress.encode(*args, codec=codec, threads=-1, **options)
    with pytest.raises(ValueError, match='threads'):
        animcompress.decode(one, threads=5000)


def test_connectivity_in_pieces_is_format_2_and_decodes_the_same(sequence):
    args = (sequence['frames'][:20], sequence['faces'])
    whole = animcompress.encode(*args, codec='trajectory', max_error=0.01, connectivity_piece=0)
    pieces = animcompress.encode(*args, codec='trajectory', max_error=0.01, connectivity_piece=100)
    assert animcompress.encode(*args, codec='trajectory', max_error=0.01) == whole  # 680 triangles: one piece
    assert (whole[4], pieces[4]) == (1, 2)  # Format_Version
    assert animcompress.info(pieces)['format_version'] == 2
    frames, faces = animcompress.decode(pieces, threads=2)
    assert np.array_equal(frames, animcompress.decode(whole)[0])
    assert np.array_equal(faces, sequence['faces'])
    with pytest.raises(ValueError, match='connectivity_piece'):
        animcompress.encode(*args, connectivity_piece=-1)


def test_join_equals_the_whole_encode(sequence, tmp_path):
    frames, faces = sequence['frames'], sequence['faces']
    whole = animcompress.encode(frames, faces, codec='auto', iframe_interval=40)
    parts = [animcompress.encode(frames[a:b], faces, codec='auto', iframe_interval=40)
             for a, b in ((0, 80), (80, 120), (120, len(frames)))]
    assert animcompress.join(parts) == whole
    first = tmp_path / 'part0.ams'
    first.write_bytes(parts[0])
    assert animcompress.join([first, bytearray(parts[1]), parts[2]]) == whole
    other = animcompress.encode(frames[80:], faces, codec='trajectory', iframe_interval=40)
    with pytest.raises(animcompress.Error, match='differ'):
        animcompress.join([parts[0], other])


def test_a_false_switch_is_left_out(sequence):
    args = (sequence['frames'][:20], sequence['faces'])
    plain = animcompress.encode(*args, codec='wavelet', step=0.001)
    assert animcompress.encode(*args, codec='wavelet', step=0.001, i_frames_only=False) == plain
    assert animcompress.encode(*args, codec='wavelet', step=0.001, i_frames_only=True) != plain


def test_random_access_equals_decoding_everything(sequence, grouped):
    everything = animcompress.decode(grouped)[0]
    decoder = animcompress.open(grouped)
    assert len(decoder) == len(everything) == len(sequence['frames'])
    assert np.array_equal(decoder[17], everything[17])
    assert np.array_equal(decoder[-1], everything[-1])
    assert np.array_equal(decoder.frame(-len(everything)), everything[0])
    assert np.array_equal(decoder.faces, sequence['faces'])
    assert np.array_equal(animcompress.decode(grouped, range(15, 25))[0], everything[15:25])
    assert np.array_equal(animcompress.decode(grouped, slice(None, None, -40))[0], everything[::-40])
    assert np.array_equal(animcompress.decode(grouped, [33, -1, 3])[0], everything[[33, -1, 3]])
    decoder.verify()


def test_one_decoder_shared_by_threads(grouped):
    everything = animcompress.decode(grouped)[0]
    decoder = animcompress.open(grouped)
    wrong = []

    def read(order):
        wrong.extend(k for k in order if not np.array_equal(decoder[k], everything[k]))

    threads = [threading.Thread(target=read, args=(np.random.default_rng(t).permutation(60),)) for t in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert wrong == []


def test_info_of_bytes_and_of_a_file(grouped, tmp_path):
    path = tmp_path / 'grouped.ams'
    path.write_bytes(grouped)
    info = animcompress.info(grouped)
    assert animcompress.info(path) == animcompress.info(str(path)) == animcompress.open(path).info() == info
    assert info['codec'] == 'affine-octree' and info['iframe_interval'] == 10
    assert info['groups'] == -(-info['frames'] // 10) and info['bytes'] == len(grouped)
    assert info['vertices'] == 342 and info['frame_rate'] == 25.0
    assert info['settings']['max_error_setting'] == 0.01 and info['settings']['profile'] == 'predictive'
    assert 'max error 0.01' in info['settings_text']


def test_open_keeps_the_bytes_alive(grouped):
    data = bytes(grouped)
    before = sys.getrefcount(data)
    decoder = animcompress.open(data)
    assert sys.getrefcount(data) > before
    expected = decoder[5]
    del data
    assert np.array_equal(decoder[5], expected)
    # A bytearray is copied (another thread could change it while frames decode).
    mutable = bytearray(grouped)
    from_bytearray = animcompress.open(mutable)
    mutable[:] = b'\0' * len(mutable)
    assert np.array_equal(from_bytearray[5], expected)
    assert np.array_equal(animcompress.decode(memoryview(grouped))[0][5], expected)


def raises_status(code, call, *args, **kwargs):
    with pytest.raises(animcompress.Error) as caught:
        call(*args, **kwargs)
    assert caught.value.code == code, str(caught.value)
    assert str(caught.value)


def test_bad_streams_raise_the_status_code(grouped, tmp_path):
    raises_status('i/o error', animcompress.open, tmp_path / 'missing.ams')
    raises_status('truncated', animcompress.decode, grouped[:len(grouped) // 2])
    flipped = bytearray(grouped)
    flipped[len(flipped) // 2] ^= 0x10
    raises_status('corrupt', animcompress.decode, flipped)
    with pytest.raises(animcompress.Error):
        animcompress.decode(b'not an animcompress stream')
    with pytest.raises(TypeError):
        animcompress.decode(12345)
    assert issubclass(animcompress.Error, Exception)


def test_bad_arrays_raise(sequence):
    frames, faces = sequence['frames'][:5], sequence['faces']
    for bad_frames in (frames[:, :, :2], frames[0], 'frames'):
        with pytest.raises(ValueError):
            animcompress.encode(bad_frames, faces)
    for bad_faces in (faces[:, :2], faces.astype(np.float32), faces.astype(np.int64) - 1, faces + np.uint64(2**32)):
        with pytest.raises(ValueError):
            animcompress.encode(frames, bad_faces)
    raises_status('bad input', animcompress.encode, frames, faces + 1000)
    with_nan = frames.copy()
    with_nan[3, 7, 1] = np.nan
    raises_status('bad input', animcompress.encode, with_nan, faces)
    raises_status('invalid argument', animcompress.encode, frames, faces, no_such_option=1)
    raises_status('invalid argument', animcompress.encode, frames, faces, max_error=-1.0)
    with pytest.raises(ValueError):
        animcompress.compare(frames, frames[:4])


def test_frames_out_of_range_raise_index_error(grouped):
    count = animcompress.info(grouped)['frames']
    decoder = animcompress.open(grouped)
    for k in (count, -count - 1):
        with pytest.raises(IndexError):
            decoder[k]
    with pytest.raises(IndexError):
        animcompress.decode(grouped, [0, count])
    with pytest.raises(TypeError):
        animcompress.decode(grouped, [1.5])


def test_decoder_limits(grouped):
    raises_status('limit exceeded', animcompress.decode, grouped, max_vertex_frames=10)
    with pytest.raises(TypeError):
        animcompress.decode(grouped, max_vertex_frames=1e9)
    with pytest.raises(ValueError):
        animcompress.decode(grouped, max_vertex_frames=-1)
    with pytest.raises(animcompress.Error) as caught:
        animcompress.open(grouped, max_vertex_frames=10)[17]
    assert caught.value.code == 'limit exceeded'
    raises_status('invalid argument', animcompress.decode, grouped, max_bitplanes=2)  # not a wavelet stream


def test_every_selection_is_bounded_by_the_work_limit(grouped):
    # The array of a repeated or strided selection holds len(frames) x N vertices, which the
    # decoder's own check (runs of frames) does not see: refused before it is made.
    vertices = animcompress.info(grouped)['vertices']
    assert animcompress.decode(grouped, frames=[0] * 10, max_vertex_frames=10 * vertices)[0].shape[0] == 10
    raises_status('limit exceeded', animcompress.decode, grouped, frames=[0] * 11, max_vertex_frames=10 * vertices)
    assert len(animcompress.decode(grouped, frames=slice(None, 20, 2), max_vertex_frames=10 * vertices)[0]) == 10
    raises_status('limit exceeded', animcompress.decode, grouped, frames=slice(None, 22, 2),
                  max_vertex_frames=10 * vertices)


def test_every_selection_is_bounded_by_the_output_limit(grouped):
    # max_output_bytes bounds the float32 array decode() returns, and what open()[k] gives.
    vertices = animcompress.info(grouped)['vertices']
    one_frame = 12 * vertices
    assert animcompress.decode(grouped, frames=range(3), max_output_bytes=3 * one_frame)[0].shape[0] == 3
    for frames in (range(4), [0] * 4, slice(None, 8, 2)):
        with pytest.raises(animcompress.Error) as caught:
            animcompress.decode(grouped, frames=frames, max_output_bytes=3 * one_frame)
        assert caught.value.code == 'limit exceeded' and 'max_output_bytes' in str(caught.value)
    assert animcompress.open(grouped, max_output_bytes=one_frame)[5].shape == (vertices, 3)
    raises_status('limit exceeded', lambda: animcompress.open(grouped, max_output_bytes=one_frame - 1)[5])
    with pytest.raises(ValueError):
        animcompress.decode(grouped, max_output_bytes=-1)


def test_a_trajectory_group_costing_more_multiply_adds_is_refused(sequence):
    # A trajectory group costs 3 x components x vertices x frames multiply-adds to rebuild.
    frames = sequence['frames'][:20]
    data = animcompress.encode(frames, sequence['faces'], codec='trajectory', target_kg=0.3)
    vertices = frames.shape[1]
    assert animcompress.decode(data, max_multiply_adds=3 * vertices * vertices * 20)[0].shape == frames.shape
    raises_status('limit exceeded', animcompress.decode, data, max_multiply_adds=3 * vertices * 20 - 1)
    raises_status('limit exceeded', lambda: animcompress.open(data, max_multiply_adds=1)[0])
    with pytest.raises(ValueError):
        animcompress.decode(data, max_multiply_adds=-1)


def test_progressive_decoding_is_coarser(sequence):
    # Cuts need frames that do not code against the previous frame's contexts.
    data = animcompress.encode(sequence['frames'][:30], sequence['faces'], codec='wavelet', i_frames_only=True)
    whole = animcompress.compare(sequence['frames'][:30], animcompress.decode(data)[0])['kg_error']
    cut = animcompress.compare(sequence['frames'][:30], animcompress.decode(data, max_bitplanes=3)[0])['kg_error']
    assert cut > whole


def grid(columns, rows):
    """A flat grid of columns x rows vertices and its triangles (two per square)."""
    u, v = np.meshgrid(np.arange(columns, dtype=np.float32), np.arange(rows, dtype=np.float32))
    points = np.stack([u.ravel(), v.ravel(), np.zeros(u.size, np.float32)], axis=1)
    corner = (np.arange(rows - 1)[:, None] * columns + np.arange(columns - 1)[None, :]).ravel()
    faces = np.concatenate([np.stack([corner, corner + 1, corner + columns], axis=1),
                            np.stack([corner + 1, corner + columns + 1, corner + columns], axis=1)])
    return points, faces.astype(np.int64)


def test_large_arrays(tmp_path):
    points, faces = grid(500, 400)  # 200 000 vertices
    frames = np.stack([points + [0, 0, 1] * np.sin(points[:, :1] * 0.05 + t) for t in range(3)]).astype(np.float64)
    data = animcompress.encode(frames, faces, max_error=0.01)
    decoded, decoded_faces = animcompress.decode(data)
    assert decoded.shape == (3, 200_000, 3) and decoded_faces.shape == faces.shape
    assert np.array_equal(decoded_faces, faces)
    assert animcompress.compare(frames, decoded)['max_error_rel_cube'] <= 0.01 + 1e-6
