// Runs the Khronos glTF validator (npm gltf-validator) on one .glb/.gltf file and prints its
// report's issue counts as one JSON line: {"errors":N,"warnings":N,"infos":N,"messages":[...]}.
// usage: node gltf_validate.js NODE_MODULES_DIR FILE
const path = require('path');
const fs = require('fs');
const validator = require(path.join(process.argv[2], 'gltf-validator'));
const file = process.argv[3];
validator
    .validateBytes(new Uint8Array(fs.readFileSync(file)), {
        uri: path.basename(file),
        maxIssues: 50,
        externalResourceFunction: (uri) =>
            Promise.reject(new Error('no external resources: ' + uri)),
    })
    .then((report) => {
        const m = report.issues.messages.map(
            (x) => x.severity + ' ' + x.code + ' ' + x.pointer + ' ' + x.message);
        console.log(JSON.stringify({
            errors: report.issues.numErrors,
            warnings: report.issues.numWarnings,
            infos: report.issues.numInfos,
            messages: m,
        }));
    })
    .catch((e) => {
        console.log(JSON.stringify({errors: -1, warnings: -1, infos: -1, messages: [String(e)]}));
        process.exit(1);
    });
