// Builds the viewer into dist/: the protobuf descriptor of proto/kerf/v1/frame.proto (with the
// messages it imports) as JSON, then one bundle of the app with esbuild. Nothing is fetched.
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdirSync } from 'node:fs';
import * as esbuild from 'esbuild';

mkdirSync('src/generated', { recursive: true });
execFileSync('node_modules/.bin/pbjs', ['-t', 'json', '-p', '../proto', '-o',
  'src/generated/kerf.json', '../proto/kerf/v1/frame.proto'], { stdio: 'inherit' });
mkdirSync('dist', { recursive: true });
await esbuild.build({
  entryPoints: ['src/main.js'], bundle: true, format: 'esm', minify: true, sourcemap: true,
  outfile: 'dist/app.js', loader: { '.json': 'json' }, logLevel: 'warning',
});
copyFileSync('src/index.html', 'dist/index.html');
console.log('web: built dist/');
