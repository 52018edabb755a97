using Drape.Core;
using UnityEngine;
using UnityEngine.Serialization;

namespace Drape
{
    /// <summary>An on-screen overlay with what the paper's app showed: step time, model, backend,
    /// vertex count and parameters. Drawn with GUI.* only (useGUILayout off: no layout pass). The
    /// text is formatted into a reused char buffer a few times per second; a new string is made only
    /// when that text changed, so frames between refreshes allocate nothing and a refresh allocates
    /// at most one string of the panel's text.</summary>
    [DisallowMultipleComponent]
    [AddComponentMenu("Drape/Drape HUD")]
    [HelpURL(DrapeDocs.Manual + "#drapehud")]
    public sealed class DrapeHud : MonoBehaviour
    {
        [Tooltip("The cloth to show; the first one found in the scene when empty (looked for once a second).")]
        [SerializeField, FormerlySerializedAs("Cloth")] private DrapeCloth _cloth;

        [Tooltip("Seconds between text refreshes.")]
        [SerializeField, FormerlySerializedAs("RefreshInterval"), Range(0.05f, 2f)] private float _refreshInterval = 0.25f;

        [Tooltip("Screen position and size of the panel, pixels.")]
        [SerializeField, FormerlySerializedAs("Panel")] private Rect _panel = new Rect(10, 10, 320, 170);

        public DrapeCloth Cloth { get => _cloth; set { _cloth = value; _nextRefresh = 0f; } }
        public float RefreshInterval { get => _refreshInterval; set => _refreshInterval = Mathf.Clamp(value, 0.05f, 2f); }
        public Rect Panel { get => _panel; set => _panel = value; }

        /// <summary>The text shown (for tests and for scripts that draw it elsewhere).</summary>
        public string Text => _shown;

        private readonly DrapeHudText _text = new DrapeHudText(512);
        private string _shown = string.Empty;
        private float _nextRefresh;
        private float _nextSearch;
        private float _smoothedMs;

        private void Awake() => useGUILayout = false;

        private void Update()
        {
            float now = Time.unscaledTime;
            if (_cloth == null)
            {
                if (now < _nextSearch) return;
                _nextSearch = now + 1f;
                _cloth = FindAnyObjectByType<DrapeCloth>();
                if (_cloth == null) return;
            }
            float ms = _cloth.LastStats.StepMs;
            _smoothedMs = _smoothedMs <= 0f ? ms : Mathf.Lerp(_smoothedMs, ms, 0.1f);
            if (now < _nextRefresh) return;
            _nextRefresh = now + _refreshInterval;
            _text.Format(_cloth, _smoothedMs);
            if (!_text.Equals(_shown)) _shown = _text.ToString();
        }

        private void OnGUI()
        {
            GUI.Box(_panel, GUIContent.none);
            GUI.Label(new Rect(_panel.x + 8, _panel.y + 6, _panel.width - 16, _panel.height - 12), _shown);
        }
    }

    /// <summary>The HUD's text, formatted into a fixed char buffer with no allocation (numbers digit
    /// by digit: number-to-string calls allocate under Unity's Mono).</summary>
    internal sealed class DrapeHudText
    {
        private readonly char[] _buffer;
        private int _length;

        public DrapeHudText(int capacity) => _buffer = new char[capacity];

        public int Length => _length;

        public void Format(DrapeCloth cloth, float stepMs)
        {
            Stats s = cloth.LastStats;
            bool gpu = cloth.ActiveBackend == Backend.Gles;
            _length = 0;
            Append(gpu ? "Drape  record " : "Drape  step ").Append(stepMs, 2).Append(gpu ? " ms (GPU time not measured)\n" : " ms\n");
            Append("model ").Append(ModelName(cloth.Model)).Append("  backend ").Append(BackendName(cloth.ActiveBackend)).Append('\n');
            Append("vertices ").Append(cloth.VertexCount).Append('\n');
            Append("substeps ").Append((long)s.Substeps).Append("  iterations ").Append((long)s.Iterations).Append('\n');
            Append("stiffness ").Append(cloth.StructuralStiffness, 2).Append(" / ").Append(cloth.ShearStiffness, 2)
                .Append(" / ").Append(cloth.BendStiffness, 2).Append(cloth.Model == Model.Pbd ? "\n" : " N/m\n");
            Append("damping ").Append(cloth.Damping, 3).Append("  mass ").Append(cloth.TotalMass, 3).Append(" kg\n");
            if (gpu) Append("strain: not read back from the GPU");
            else Append("max strain ").Append(s.MaxStrain * 100f, 1).Append(" %");
            if (cloth.IsAsleep) Append("  (asleep)");
            if (cloth.UnstableEvents > 0) Append("\nrolled back ").Append(cloth.UnstableEvents).Append(" steps");
        }

        public static string ModelName(Model m) =>
            m == Model.Xpbd ? "XPBD" : m == Model.Pbd ? "PBD" : m == Model.MassSpring ? "mass-spring" :
            m == Model.Implicit ? "implicit" : m == Model.Auto ? "auto" : "?";

        public static string BackendName(Backend b) =>
            b == Backend.Gles ? "GPU (GLES)" : b == Backend.CpuThreaded ? "CPU threaded" : b == Backend.Cpu ? "CPU" : "?";

        public DrapeHudText Append(string text)
        {
            for (int i = 0; i < text.Length && _length < _buffer.Length; ++i) _buffer[_length++] = text[i];
            return this;
        }

        public DrapeHudText Append(char c)
        {
            if (_length < _buffer.Length) _buffer[_length++] = c;
            return this;
        }

        public DrapeHudText Append(long value)
        {
            if (value < 0)
            {
                Append('-');
                value = -value;
            }
            int start = _length;
            do
            {
                Append((char)('0' + (int)(value % 10)));
                value /= 10;
            } while (value > 0);
            System.Array.Reverse(_buffer, start, _length - start);
            return this;
        }

        /// <summary>Fixed-point with <paramref name="decimals"/> digits (rounded); NaN and huge values in words.</summary>
        public DrapeHudText Append(float value, int decimals)
        {
            if (float.IsNaN(value)) return Append("NaN");
            if (value < 0f)
            {
                Append('-');
                value = -value;
            }
            if (value > 1e15f) return Append("inf");
            long scale = 1;
            for (int i = 0; i < decimals; ++i) scale *= 10;
            long fixedPoint = (long)(value * scale + 0.5f);
            Append(fixedPoint / scale);
            if (decimals == 0) return this;
            Append('.');
            long frac = fixedPoint % scale;
            for (long d = scale / 10; d > 0; d /= 10)
            {
                Append((char)('0' + (int)(frac / d)));
                frac %= d;
            }
            return this;
        }

        public bool Equals(string shown)
        {
            if (shown == null || shown.Length != _length) return false;
            for (int i = 0; i < _length; ++i)
                if (shown[i] != _buffer[i]) return false;
            return true;
        }

        public override string ToString() => new string(_buffer, 0, _length);
    }
}
