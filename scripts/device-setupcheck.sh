source scripts/device-env.sh
"$bin/tessera" bench --device gpu --scene grid --objects 100000 --size 1920x1080 --backends hardware --repeat 20 --warmup-ms 3000 --quiet
for r in 1 2; do for v in before after inlineclip; do
  b=$bin; [[ $v == before ]] && b=$PWD/.device-before; [[ $v == inlineclip ]] && b=$PWD/.device-variants/inlineclip
  lib=$bin; [[ $v == before ]] && lib=$b
  LD_LIBRARY_PATH=$lib $b/tessera bench --device gpu --scene grid --objects 1000000 --size 1920x1080 --backends compute --repeat 10 --runs 1 --warmup-ms 300 --json /tmp/$v.json > /dev/null
  python3 -c "import json; d=json.load(open('/tmp/$v.json')); r=d['results'][0]; print('$v', r['total_ms'], r['passes_ms']['setup'])"
done; done
