#!/usr/bin/env bash
# The pacs tests' shared fixture: starts Orthanc (tests/pacs/orthanc.sh), writes DICOM series with the
# project's GDCM writer (vots_write_dicom) into STATE_DIR/series and uploads them through Orthanc's REST API.
#
# Usage: tests/pacs/pacs_setup.sh STATE_DIR WRITE_DICOM_TOOL   (ctest: FIXTURES_SETUP Orthanc)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
state=${1:?usage: pacs_setup.sh STATE_DIR WRITE_DICOM_TOOL}
tool=${2:?usage: pacs_setup.sh STATE_DIR WRITE_DICOM_TOOL}
cranium=${VOTS_CRANIUM_HEADER:-$here/../../data/cranium.nhdr}

"$here/orthanc.sh" start "$state"
series=$state/series
mkdir -p "$series"
# Study UID = series UID + ".0" (the writer's rule); tests/pacs/pacs_cli.sh names them.
"$tool" "$series/ramp" --synthetic ramp --dims 32,24,20 --spacing 0.8,0.8,1.25 --series-uid 1.2.826.0.1.3680043.10.1234.201 \
    --description ramp
"$tool" "$series/cranium" --input "$cranium" --unsigned --bits-stored 12 --intercept -1024 --description Cranium \
    --orientation 1,0,0,0,-1,0 --slices-against-normal --series-uid 1.2.826.0.1.3680043.10.1234.202
"$tool" "$series/mixed" --synthetic ramp --dims 32,24,20 --spacing 0.8,0.8,1.25 --resize-slice 3 \
    --series-uid 1.2.826.0.1.3680043.10.1234.203 --description mixed

# The source of the sweep stored back (pacs_cli.sh SweepStoredOnThePacs), in a study of its own.
"$tool" "$series/sweep-source" --synthetic sphere --dims 32,32,24 --series-uid 1.2.826.0.1.3680043.10.1234.206 \
    --description sweep-source

# The source of the sweeps the server sends (test_ServerPacsStore.cpp, the viewer's spec), in a study of its
# own: the series counts of the others stay as their tests expect them.
"$tool" "$series/send-source" --synthetic sphere --dims 32,32,24 --series-uid 1.2.826.0.1.3680043.10.1234.207 \
    --description send-source

port=$(cat "$state/port")
for file in "$series"/*/*; do
    curl -fsS -u "vots:$(cat "$state/password")" -X POST --data-binary "@$file" \
        -H 'Content-Type: application/dicom' "http://127.0.0.1:$port/instances" -o /dev/null
done
# Instances that are not images (a structured report made by Orthanc itself): a series of one, and one
# beside the images of a ramp (the writer's PatientID: Orthanc files an instance under patient, study and
# series, so another patient's report would make a series of its own).
"$tool" "$series/with-report" --synthetic ramp --dims 32,24,20 --spacing 0.8,0.8,1.25 \
    --series-uid 1.2.826.0.1.3680043.10.1234.205 --description with-report
for file in "$series/with-report"/*; do
    curl -fsS -u "vots:$(cat "$state/password")" -X POST --data-binary "@$file" \
        -H 'Content-Type: application/dicom' "http://127.0.0.1:$port/instances" -o /dev/null
done
for uid in 1.2.826.0.1.3680043.10.1234.204 1.2.826.0.1.3680043.10.1234.205; do
    curl -fsS -u "vots:$(cat "$state/password")" -X POST "http://127.0.0.1:$port/tools/create-dicom" -o /dev/null \
        -d '{"Force": true, "Tags": {"PatientName": "Vots^Phantom", "PatientID": "VOTS-PHANTOM-1", "StudyInstanceUID": "'$uid'.0", "SeriesInstanceUID": "'$uid'",
             "SOPClassUID": "1.2.840.10008.5.1.4.1.1.88.11", "Modality": "SR"}}'
done
echo "pacs_setup: Orthanc on 127.0.0.1:$port holds $(find "$series" -type f | wc -l) instances"
